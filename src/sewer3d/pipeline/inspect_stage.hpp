#pragma once
/// \file
/// The inspection stage (issue 18; docs/inspection.md): the pipe model's maps (WS/model/, whole
/// files or tiles, read piece by piece so memory stays bounded) become EN 13508-2 observations
/// and the cross-section profile, in WS/inspection/: observations.json / .csv / .xml
/// (ISYBAU-style), profile.csv, crops/<id>.png (the map around each observation: texture above,
/// displacement below) and report.json.

#include <functional>
#include <string>

#include "sewer3d/inspect/inspect.hpp"
#include "sewer3d/inspect/profile.hpp"
#include "sewer3d/pipeline/workspace.hpp"
#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

struct InspectStageOptions {
  InspectOptions inspect;
  ProfileOptions profile;
  int max_crop_side_px = 800;  ///< crops larger than this are scaled down
  bool force = false;
  void Check() const;
};

/// The options that decide the outputs, as workspace.json records them.
std::string InspectOptionsJson(const InspectStageOptions& options);

struct InspectStageReport {
  bool ok = false;
  std::string message;  ///< why not, one line
  InspectionReport inspection;
  int observations = 0;
  std::map<std::string, int> per_code;
  int profile_rows = 0, profile_rows_measured = 0;
  double inspected_from_mm = 0.0, inspected_to_mm = 0.0;  ///< stations with a smooth wall
  double seconds = 0.0;
};

std::string InspectStageReportToJson(const InspectStageReport& report);

/// Progress of the passes ("maps", "crops").
using InspectProgress = std::function<void(const std::string& pass, int finished, int total)>;

/// Runs the inspection stage on the model in `workspace`. Throws std::invalid_argument on
/// invalid options, WorkspaceConflict, FileError when the model is missing or unreadable.
InspectStageReport RunInspectStage(const CaptureRun& run, Workspace& workspace,
                                   const InspectStageOptions& options,
                                   const InspectProgress& progress = {});

}  // namespace sewer3d
