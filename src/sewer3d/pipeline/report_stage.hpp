#pragma once
/// \file
/// The report stage (issue 18 items 4–5; docs/report.md): WS/report/index.html, one
/// self-contained offline page of what the workspace holds — run summary, the unrolled maps,
/// the 3D viewer, the profile, the observations with their crops and, where evaluations were
/// run (simulated runs), the accuracy figures. What is missing is said on the page.

#include <filesystem>
#include <string>
#include <vector>

#include "sewer3d/pipeline/workspace.hpp"
#include "sewer3d/report/report.hpp"
#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

struct ReportStageReport {
  ReportSummary summary;
  std::filesystem::path html;
  /// Stage outputs shown that are not the files their stage wrote (one line each).
  std::vector<std::string> warnings;
  int observations = -1;  ///< −1: none computed
  int profile_rows = -1;
  double seconds = 0.0;
};

/// Writes WS/report/index.html for `run` (the stage "report" in workspace.json). FileError when
/// the workspace's files are malformed or the page cannot be written; a missing model is said
/// on the page (summary.maps_problem), not an error.
ReportStageReport RunReportStage(const CaptureRun& run, Workspace& workspace, bool force);

}  // namespace sewer3d
