#pragma once
/// \file
/// The RGB-D stage over a whole capture run (issue 14, deliverable 2; DESIGN.md contract
/// "processing workspace"): for every acquisition, decode and triangulate the pattern image
/// with its module's FrameReconstructor (triangulate/reconstruct_frame.hpp) and write
/// `WS/rgbd/m<k>/<counter>_color.png`, `_depth.tiff`, `_cloud.ply` and `_report.json` (last),
/// then the stage report `WS/rgbd/report.json` (docs/rgbd.md).
///
/// Colour is the acquisition's texture_before image as captured (kRgbdColorSource): shading
/// and colour correction, deblur and the texture → 3D mapping at the pattern instant (issue
/// 14, deliverables 3–5) are not done yet.
///
/// Streaming: each worker holds one acquisition's images at a time and one FrameReconstructor
/// per module. Resumable: an acquisition whose report exists is skipped. A bad image fails
/// only its own acquisition, listed with the file and reason; the others are processed.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "sewer3d/pipeline/workspace.hpp"
#include "sewer3d/run/capture_run.hpp"
#include "sewer3d/triangulate/reconstruct_frame.hpp"

namespace sewer3d {

/// Where the colour of the RGB-D outputs comes from, as recorded in workspace.json and the
/// reports.
inline constexpr const char* kRgbdColorSource = "texture_before, uncorrected";

struct RgbdStageOptions {
  FrameReconstructionOptions reconstruction;  ///< decoder, triangulation, depth map
  /// Acquisitions processed at once (≥ 1), each worker holding one acquisition's images and
  /// one FrameReconstructor per module it has met. Does not change the outputs.
  int threads = 1;
  /// Redo the stage from scratch (Workspace::BeginStage), even with other options recorded.
  bool force = false;
  /// Throws std::invalid_argument naming the option.
  void Check() const;
};

/// The options that decide the outputs, as workspace.json records them (compact JSON with
/// sorted keys): triangulation depth range and reprojection limit, outlier rejection,
/// max_edge_steps. Decoder options are the defaults (not settable from the command line).
std::string RgbdOptionsJson(const RgbdStageOptions& options);

/// What happened to one acquisition.
struct RgbdAcquisitionResult {
  enum class Status { kDone, kSkipped, kFailed };
  int module = 0;
  int counter = 0;
  Status status = Status::kDone;
  std::string file;    ///< kFailed: the file at fault (as the run names it, or the output)
  std::string reason;  ///< kFailed: one line
  FrameReport frame;   ///< kDone: spots, points, rejections, stage times
  double seconds = 0;  ///< kDone: reading, reconstruction and writing
};

/// The stage's report (`WS/rgbd/report.json`, RgbdStageReportToJson).
struct RgbdStageReport {
  int acquisitions = 0;  ///< in the run
  int done = 0;          ///< processed now
  int skipped = 0;       ///< already done by an earlier run (report present)
  int failed = 0;
  std::vector<RgbdAcquisitionResult> results;  ///< ordered by (module, counter)
  long long spots = 0;                         ///< over the acquisitions done now
  long long points = 0;
  double seconds = 0;                  ///< the whole stage, wall clock
  double seconds_per_acquisition = 0;  ///< mean over those done now (one worker's time)
  double max_seconds_per_acquisition = 0;
  int threads = 1;
  /// The first failed acquisition in (module, counter) order; null when none failed.
  const RgbdAcquisitionResult* FirstFailure() const;
};

/// The report as JSON text (keys sorted; format in docs/rgbd.md).
std::string RgbdStageReportToJson(const RgbdStageReport& report);

/// Called after every acquisition (done, skipped or failed) from the thread that finished it,
/// never from two threads at once.
using StageProgress = std::function<void(int finished, int total)>;

/// Runs the RGB-D stage of `run` into `workspace` (records it there, workspace.hpp). Throws
/// std::invalid_argument on invalid options, WorkspaceConflict when the stage was recorded with
/// other options and !options.force, FileError when the rig cannot decode (a module's pattern
/// fails InferConstraints) or the workspace cannot be written. Failures of single acquisitions
/// are in the report, not thrown.
RgbdStageReport RunRgbdStage(const CaptureRun& run, Workspace& workspace,
                             const RgbdStageOptions& options, const StageProgress& progress = {});

}  // namespace sewer3d
