// sewer3d: one binary, one subcommand per task (DESIGN.md, command-line contract).
// Errors end here: one line on stderr and the exit status of cli/exit_code.hpp (README's table).

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <iostream>
#include <vector>

#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/exit_code.hpp"
#include "sewer3d/cli/library_logs.hpp"

namespace {

int ReportError(const std::exception_ptr& error) {
  const sewer3d::cli::ErrorExit exit = sewer3d::cli::ExitForError(error);
  std::cerr << "sewer3d: error: " << exit.message << "\n";
  return exit.code;
}

}  // namespace

int main(int argc, char** argv) {
  sewer3d::cli::QuietLibraryLogs();
  CLI::App app{"sewer3d: metric 3D models of sewer pipes from structured-light inspection"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show help for every subcommand");
  const std::vector<sewer3d::cli::Command> commands = {
      sewer3d::cli::AddModuleCommand(app),   sewer3d::cli::AddPatternCommand(app),
      sewer3d::cli::AddDescribeCommand(app), sewer3d::cli::AddPoseGraphCommand(app),
      sewer3d::cli::AddSimulateCommand(app), sewer3d::cli::AddReconstructCommand(app),
      sewer3d::cli::AddEvaluateCommand(app), sewer3d::cli::AddCalibrateCommand(app),
      sewer3d::cli::AddRgbdCommand(app),     sewer3d::cli::AddRegisterCommand(app),
      sewer3d::cli::AddModelCommand(app),    sewer3d::cli::AddInspectCommand(app),
      sewer3d::cli::AddProcessCommand(app),  sewer3d::cli::AddDemoCommand(app),
      sewer3d::cli::AddReportCommand(app),
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::cout << app.help("", CLI::AppFormatMode::All);
    return 0;
  } catch (const CLI::ParseError& e) {
    // Subcommand --help arrives here too, as CallForHelp raised inside the subcommand.
    if (e.get_exit_code() == 0) {
      for (const auto& c : commands) {
        if (c.app->parsed()) {
          const CLI::App* deepest = c.app;
          for (const CLI::App* sub : c.app->get_subcommands()) deepest = sub;
          std::cout << deepest->help();
          return 0;
        }
      }
      std::cout << app.help();
      return 0;
    }
    return ReportError(std::current_exception());
  }
  try {
    for (const auto& c : commands) {
      if (c.app->parsed()) return c.run();
    }
    std::cerr << "sewer3d: error: no subcommand\n";
    return sewer3d::cli::kExitUsage;
  } catch (...) {
    return ReportError(std::current_exception());
  }
}
