// sewer3d: one binary, one subcommand per task (DESIGN.md, command-line contract).
// Errors end here: one line on stderr and the exit status of cli/exit_code.hpp (README's table).

#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/argv_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/exit_code.hpp"
#include "sewer3d/cli/library_logs.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/pipeline/workspace.hpp"

namespace {

int ReportError(const std::exception_ptr& error) {
  const sewer3d::cli::ErrorExit exit = sewer3d::cli::ExitForError(error);
  fmt::print(stderr, "sewer3d: error: {}\n", exit.message);
  return exit.code;
}

// Commands whose outputs belong together, so that a failure part-way (a full disk) leaves none
// of them (NewOutputs). The stages, `process`, `demo` and `simulate run` keep what they wrote,
// to resume from it.
bool WritesOneSet(const CLI::App& command) {
  const std::string& name = command.get_name();
  if (name == "simulate") {
    const auto subs = command.get_subcommands();
    return !subs.empty() && subs.front()->get_name() != "run";
  }
  return name == "module" || name == "pattern" || name == "reconstruct" || name == "evaluate" ||
         name == "calibrate";
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
  app.set_version_flag("--version", sewer3d::SoftwareVersion());
  // An unknown first word is named (CLI11 would only say that a subcommand is required).
  std::string names;
  bool known = false;
  for (const auto& c : commands) {
    names += (names.empty() ? "" : ", ") + c.app->get_name();
    known |= argc >= 2 && c.app->get_name() == argv[1];
  }
  if (argc >= 2 && argv[1][0] != '-' && !known) {
    fmt::print(stderr, "sewer3d: error: unknown command '{}'; the commands are {}\n", argv[1],
               names);
    return sewer3d::cli::kExitUsage;
  }
  if (const std::string arg = sewer3d::cli::SingleDashLongOption(app, argc, argv); !arg.empty()) {
    fmt::print(stderr,
               "sewer3d: error: {}: long options take two dashes: -{} (see sewer3d --help)\n", arg,
               arg);
    return sewer3d::cli::kExitUsage;
  }
  std::string problem = sewer3d::cli::UnknownLongOption(app, argc, argv);
  if (problem.empty()) problem = sewer3d::cli::FlagGivenAsValue(app, argc, argv);
  if (!problem.empty()) {
    fmt::print(stderr, "sewer3d: error: {} (see sewer3d --help)\n", problem);
    return sewer3d::cli::kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << "\n";
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
    if (const std::string missing = sewer3d::cli::MissingArgument(app, e.what());
        !missing.empty()) {
      fmt::print(stderr, "sewer3d: error: {} (see sewer3d --help)\n", missing);
      return sewer3d::cli::kExitUsage;
    }
    // Range and conversion refusals in the words of the other value errors.
    fmt::print(
        stderr, "sewer3d: error: {} (see sewer3d --help)\n",
        sewer3d::cli::ReadableParseError(e.what(), sewer3d::cli::TakesWholeNumbers(app, e.what())));
    return sewer3d::cli::ParseErrorExit(e.what());
  }
  if (const auto [option, problem] = sewer3d::cli::BadValue(app); option != nullptr) {
    fmt::print(stderr, "sewer3d: error: invalid value: {}: {}\n", option->get_name(), problem);
    return sewer3d::cli::kExitUsage;
  }
  try {
    for (const auto& c : commands) {
      if (!c.app->parsed()) continue;
      std::optional<sewer3d::NewOutputs> outputs;
      if (WritesOneSet(*c.app)) outputs.emplace();
      const int code = c.run();
      if (code == 0 && outputs) outputs->Keep();
      return code;
    }
    fmt::print(stderr, "sewer3d: error: no subcommand\n");
    return sewer3d::cli::kExitUsage;
  } catch (...) {
    return ReportError(std::current_exception());
  }
}
