// mechkin command-line entry point. Exit codes: 0 success, 1 invalid input or a
// failed expectation/run, 2 unusable arguments. Nothing escapes main.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstring>
#include <iostream>

#include "cli/commands/bench_command.hpp"
#include "cli/commands/check_command.hpp"
#include "cli/commands/convert_command.hpp"
#include "cli/commands/foreign.hpp"
#include "cli/commands/optimize_command.hpp"
#include "cli/commands/range_command.hpp"
#include "cli/commands/run_command.hpp"
#include "cli/commands/sweep_command.hpp"
#include "cli/commands/tolerance_command.hpp"
#include "cli/commands/view_command.hpp"

int main(int argc, char** argv) {
  try {
    CLI::App app{"mechkin: spatial kinematics of mechanisms"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "mechkin 0.1.0");
    mechkin::CheckOptions check;
    mechkin::RunOptions run;
    mechkin::BenchCommandOptions bench;
    mechkin::SetupCheckCommand(app, &check);
    mechkin::SetupRunCommand(app, &run);
    mechkin::SetupBenchCommand(app, &bench);
    mechkin::ViewOptions view;
    mechkin::SetupViewCommand(app, &view);
    mechkin::ToleranceCommandOptions tolerance;
    mechkin::SetupToleranceCommand(app, &tolerance);
    mechkin::SweepCommandOptions sweep;
    mechkin::SetupSweepCommand(app, &sweep);
    mechkin::RangeCommandOptions range;
    mechkin::SetupRangeCommand(app, &range);
    mechkin::ConvertCommandOptions convert;
    mechkin::SetupConvertCommand(app, &convert);
    mechkin::OptimizeCommandOptions optimize;
    mechkin::SetupOptimizeCommand(app, &optimize);
    mechkin::ImportCommandOptions import_options;
    mechkin::SetupImportCommand(app, &import_options);
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      const int code = app.exit(e);  // prints help/version/error
      return code == 0 ? 0 : 2;      // CLI11 codes >= 100 become our "unusable arguments"
    }
    int code = 2;
    if (app.got_subcommand("check")) code = mechkin::RunCheck(check, std::cout, std::cerr);
    if (app.got_subcommand("run")) code = mechkin::RunRun(run, std::cout, std::cerr);
    if (app.got_subcommand("bench")) code = mechkin::RunBenchCommand(bench, std::cout, std::cerr);
    if (app.got_subcommand("view")) code = mechkin::RunView(view, std::cout, std::cerr);
    if (app.got_subcommand("range")) code = mechkin::RunRangeCommand(range, std::cout, std::cerr);
    if (app.got_subcommand("sweep")) code = mechkin::RunSweepCommand(sweep, std::cout, std::cerr);
    if (app.got_subcommand("convert")) code = mechkin::RunConvertCommand(convert, std::cout, std::cerr);
    if (app.got_subcommand("import")) code = mechkin::RunImportCommand(import_options, std::cout, std::cerr);
    if (app.got_subcommand("optimize")) code = mechkin::RunOptimizeCommand(optimize, std::cout, std::cerr);
    if (app.got_subcommand("tolerance")) code = mechkin::RunToleranceCommand(tolerance, std::cout, std::cerr);
    // A report that could not be written is a failure, not a success.
    std::cout.flush();
    if (!std::cout) {
      if (code == 0)
        std::cerr << "mechkin: writing to the standard output failed: " << std::strerror(errno ? errno : EIO) << "\n";
      return code == 0 ? 1 : code;
    }
    return code;
  } catch (const std::exception& e) {
    std::cerr << "mechkin: internal error: " << e.what() << "\n";
    return 1;
  } catch (...) {
    std::cerr << "mechkin: internal error\n";
    return 1;
  }
}
