// sewer3d: one binary, one subcommand per task (DESIGN.md, command-line contract).
// Errors end here: one line on stderr and a non-zero exit status.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <iostream>
#include <vector>

#include "sewer3d/cli/command.hpp"
#include "sewer3d/io/file_error.hpp"

namespace {

constexpr int kExitUsage = 2;
constexpr int kExitFile = 3;
constexpr int kExitInternal = 4;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"sewer3d: metric 3D models of sewer pipes from structured-light inspection"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show help for every subcommand");
  const std::vector<sewer3d::cli::Command> commands = {
      sewer3d::cli::AddModuleCommand(app),   sewer3d::cli::AddPatternCommand(app),
      sewer3d::cli::AddDescribeCommand(app), sewer3d::cli::AddPoseGraphCommand(app),
      sewer3d::cli::AddSimulateCommand(app), sewer3d::cli::AddReconstructCommand(app),
      sewer3d::cli::AddEvaluateCommand(app), sewer3d::cli::AddCalibrateCommand(app),
      sewer3d::cli::AddRgbdCommand(app),
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
    std::cerr << "sewer3d: error: " << e.what() << " (see sewer3d --help)\n";
    return kExitUsage;
  }
  try {
    for (const auto& c : commands) {
      if (c.app->parsed()) return c.run();
    }
    std::cerr << "sewer3d: error: no subcommand\n";
    return kExitUsage;
  } catch (const sewer3d::FileError& e) {
    std::cerr << "sewer3d: error: " << e.what() << "\n";
    return kExitFile;
  } catch (const std::invalid_argument& e) {
    std::cerr << "sewer3d: error: invalid value: " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "sewer3d: error: " << e.what() << "\n";
    return kExitInternal;
  }
}
