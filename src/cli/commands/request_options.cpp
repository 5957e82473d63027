#include "cli/commands/request_options.hpp"

#include <cerrno>
#include <cstdlib>

#include "analysis/enum_names.hpp"
#include "io/interrupt.hpp"

namespace mechkin {
namespace {

// The option's text as a number, or false when it is not one (then the message
// quotes the text as given).
bool ReadNumber(const std::string& text, double* v) {
  char* end = nullptr;
  *v = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0';
}

bool ReadInteger(const std::string& text, int* v) {
  char* end = nullptr;
  errno = 0;
  const long n = std::strtol(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0' || errno == ERANGE || n < -1000000 || n > 1000000) return false;
  *v = static_cast<int>(n);
  return true;
}

// A check that puts the value into a default request and asks IsValid: the field's
// range and message are the request's, not the command's.
CLI::Validator RequestCheck(bool (*set)(const std::string& text, RunRequest* r, std::string* why),
                            const std::string& description) {
  return CLI::Validator(
      [set](std::string& text) -> std::string {
        RunRequest r;
        std::string why;
        if (!set(text, &r, &why)) return why;
        return r.IsValid(&why) ? "" : why;
      },
      description);
}

bool SetOrder(const std::string& text, RunRequest* r, std::string* why) {
  if (ReadInteger(text, &r->order)) return true;
  *why = RunRequest::OrderProblem("'" + text + "'");
  return false;
}

bool SetTolerance(const std::string& text, RunRequest* r, std::string* why) {
  if (ReadNumber(text, &r->tolerance)) return true;
  *why = RunRequest::ToleranceProblem("'" + text + "'");
  return false;
}

}  // namespace

CLI::Validator OrderCheck() { return RequestCheck(&SetOrder, "in 0..4"); }
CLI::Validator ToleranceCheck() { return RequestCheck(&SetTolerance, "in [1e-15, 1e-3]"); }

CLI::Validator CountCheck(const CountLimit& limit) {
  return CLI::Validator(
      [limit](std::string& text) -> std::string {
        double v = 0;
        if (!ReadNumber(text, &v)) return std::string(limit.what) + " must be a whole number, not '" + text + "'";
        return CountProblem(limit, v);
      },
      "in " + std::to_string(limit.low) + ".." + std::to_string(limit.high));
}

CLI::Option* AddOrderOption(CLI::App* cmd, RunRequest* request, const std::string& description) {
  return cmd->add_option("--order", request->order, description)->check(OrderCheck());
}

CLI::Option* AddToleranceOption(CLI::App* cmd, RunRequest* request, const std::string& description) {
  return cmd->add_option("--tol", request->tolerance, description)->check(ToleranceCheck());
}

CLI::Option* AddSolverOption(CLI::App* cmd, RunRequest* request) {
  return cmd
      ->add_option_function<std::string>(
          "--solver", [request](const std::string& s) { Parse(s, &request->solver); },
          "Position solver (" + NameList<PositionSolver>() + ")")
      ->check(CLI::IsMember(NamesOf<PositionSolver>()));
}

CLI::Option* AddFormulationOption(CLI::App* cmd, RunRequest* request) {
  return cmd
      ->add_option_function<std::string>(
          "--formulation", [request](const std::string& s) { Parse(s, &request->formulation); },
          "Rotational unknowns of the derivative solves (" + NameList<Formulation>() + ")")
      ->check(CLI::IsMember(NamesOf<Formulation>()));
}

CLI::Option* AddKeepPartialOption(CLI::App* cmd, bool* keep_partial, const std::string& what) {
  return cmd->add_flag("--keep-partial", *keep_partial,
                       "On Ctrl-C (SIGINT) write " + what + " so far, marked partial (exit 130), instead of nothing");
}

InterruptPoll InstallInterruptPoll(bool keep_partial) {
  InstallInterruptHandlers(keep_partial);
  return [] { return InterruptRequested(); };
}

}  // namespace mechkin
