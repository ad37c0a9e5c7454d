#pragma once
/// \file
/// Scenario files of virtual runs (docs/formats.md, "Scenario file"). Errors are FileError
/// naming the file and the field; unknown fields are errors, not silently ignored.

#include <filesystem>
#include <string>

#include "sewer3d/sim/scenario.hpp"

namespace sewer3d {

/// Parses scenario JSON; absent fields keep Scenario's defaults. `path` names the source.
Scenario ParseScenario(const std::string& json_text, const std::filesystem::path& path);
Scenario ReadScenario(const std::filesystem::path& path);
/// The complete scenario (every field written), readable by ParseScenario.
std::string ScenarioToJson(const Scenario& scenario);
/// The scenario's `module` member for RUN/truth/scenario.json, so that the file reproduces the
/// run: `module_file` relative to RUN/truth/ (absolute where no relative path exists).
std::string ModuleFileFromTruth(const std::filesystem::path& run_folder,
                                const std::filesystem::path& module_file);
/// The pipe world alone (the same form as the scenario's "pipe" member).
std::string PipeWorldToJson(const PipeWorld& world);

}  // namespace sewer3d
