#pragma once
/// \file
/// Subcommands of the `sewer3d` binary. Each Add*Command registers its options on the app and
/// returns the function to run when that subcommand was chosen (exit code as result).

#include <CLI/CLI.hpp>
#include <algorithm>
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
        if (!digits) return "expected a whole number >= 0, got " + text;
        const std::string max = "18446744073709551615";  // 2^64 - 1
        const std::string trimmed =
            text.substr(std::min(text.find_first_not_of('0'), text.size() - 1));
        const bool fits =
            trimmed.size() < max.size() || (trimmed.size() == max.size() && trimmed <= max);
        return fits ? std::string() : "expected a whole number up to " + max + ", got " + text;
      },
      "UINT");
}

}  // namespace sewer3d::cli
