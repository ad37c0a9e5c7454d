#pragma once
/// \file
/// ReportInputs from a processing workspace: WS/model, WS/workspace.json (per-stage seconds),
/// the run's run.json (a few facts), WS/evaluation/<name>/evaluation.json. What is missing
/// becomes a note; nothing here throws for a missing or malformed file except the workspace
/// folder itself not existing (FileError).

#include <filesystem>

#include "sewer3d/report/report.hpp"

namespace sewer3d {

/// Reads what the workspace `ws` of the capture run in `run_folder` holds. Observations and the
/// profile are left to the caller (their files belong to `sewer3d inspect`).
ReportInputs GatherReportInputs(const std::filesystem::path& ws,
                                const std::filesystem::path& run_folder);

}  // namespace sewer3d
