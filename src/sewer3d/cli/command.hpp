#pragma once
/// \file
/// Subcommands of the `sewer3d` binary. Each Add*Command registers its options on the app and
/// returns the function to run when that subcommand was chosen (exit code as result).

#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>
#include <utility>

namespace sewer3d::cli {

using Runner = std::function<int()>;

struct Command {
  CLI::App* app;
  Runner run;
};

Command AddModuleCommand(CLI::App& app);
Command AddPatternCommand(CLI::App& app);
Command AddDescribeCommand(CLI::App& app);
Command AddPoseGraphCommand(CLI::App& app);
Command AddSimulateCommand(CLI::App& app);
Command AddReconstructCommand(CLI::App& app);
Command AddEvaluateCommand(CLI::App& app);
Command AddCalibrateCommand(CLI::App& app);
Command AddRgbdCommand(CLI::App& app);
Command AddRegisterCommand(CLI::App& app);
Command AddModelCommand(CLI::App& app);
Command AddInspectCommand(CLI::App& app);
Command AddProcessCommand(CLI::App& app);
Command AddDemoCommand(CLI::App& app);
Command AddReportCommand(CLI::App& app);

/// Parses "WxH" (e.g. "648x486"); nullopt when malformed or not positive.
std::optional<std::pair<int, int>> ParseSize(const std::string& text);

}  // namespace sewer3d::cli
