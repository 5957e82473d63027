// The run request's options on the command line: every command that runs the
// analysis (run, view, range, tolerance, sweep) declares --order, --tol, --solver
// and --formulation through these, so CLI11 checks each value with
// RunRequest::IsValid and prints its message ("--tol: tol must be ...").
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "analysis/count_limits.hpp"
#include "analysis/run_request.hpp"

namespace mechkin {

/// Checks of an option's text: it is put into a default RunRequest's order or
/// tolerance and RunRequest::IsValid answers (for commands whose options are not a request).
CLI::Validator OrderCheck();
CLI::Validator ToleranceCheck();
/// A count's check (analysis/count_limits.hpp): the message Python gives for the same value.
CLI::Validator CountCheck(const CountLimit& limit);
/// --order into `request->order`, checked by RunRequest::IsValid.
CLI::Option* AddOrderOption(CLI::App* cmd, RunRequest* request, const std::string& description);
/// --tol into `request->tolerance`, checked by RunRequest::IsValid.
CLI::Option* AddToleranceOption(CLI::App* cmd, RunRequest* request, const std::string& description);
/// --solver NAME into `request->solver` (names: analysis/enum_names.hpp).
CLI::Option* AddSolverOption(CLI::App* cmd, RunRequest* request);
/// --formulation NAME into `request->formulation`.
CLI::Option* AddFormulationOption(CLI::App* cmd, RunRequest* request);
/// --keep-partial: on Ctrl-C (SIGINT) the command stops at its next step and writes
/// `what` so far, marked partial, and exits 130 (as `run --keep-partial`).
CLI::Option* AddKeepPartialOption(CLI::App* cmd, bool* keep_partial, const std::string& what);
/// Installs the SIGINT/SIGTERM handlers (io/interrupt.hpp: without keep_partial a
/// signal removes the temporary output and ends the process) and returns the poll
/// the analysis asks between steps and runs.
InterruptPoll InstallInterruptPoll(bool keep_partial);
/// The exit code of an interrupted command (128 + SIGINT, as a shell reports Ctrl-C).
constexpr int kInterruptedExit = 130;

}  // namespace mechkin
