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

/// Parses "WxH" (e.g. "648x486"): digits only, each side 1..32768; nullopt otherwise.
std::optional<std::pair<int, int>> ParseSize(const std::string& text);

/// A validator for unsigned options such as --seed: digits only (CLI11 would wrap "-1" to
/// 18446744073709551615).
inline CLI::Validator Digits() {
  return CLI::Validator(
      [](std::string& text) {
        const bool digits =
            !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        return digits ? std::string() : "expected a whole number >= 0, got " + text;
      },
      "UINT");
}

}  // namespace sewer3d::cli
