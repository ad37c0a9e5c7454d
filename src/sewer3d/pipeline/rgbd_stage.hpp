#pragma once
/// \file
/// The RGB-D stage over a whole capture run (issue 14; DESIGN.md contract "processing
/// workspace"; docs/rgbd.md). Two passes over the acquisitions:
/// - geometry (rgbd_geometry.hpp): decode and triangulate the pattern image with its module's
///   FrameReconstructor; depth map, preview, cloud, `_geometry.json`;
/// - colour (rgbd_colour.hpp): the colour image aligned with the depth map, the cloud
///   recoloured, `_report.json` last;
/// then the stage report `WS/rgbd/report.json` over every acquisition of the run.
///
/// Streaming: each worker holds one acquisition's images at a time and one FrameReconstructor
/// per module. Resumable: each pass skips what an earlier run finished (its file written last
/// exists). A bad image fails only its own acquisition, listed with the file and reason; the
/// others are processed.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "sewer3d/pipeline/rgbd_colour.hpp"
#include "sewer3d/pipeline/rgbd_geometry.hpp"
#include "sewer3d/pipeline/workspace.hpp"
#include "sewer3d/run/capture_run.hpp"
#include "sewer3d/triangulate/reconstruct_frame.hpp"

namespace sewer3d {

struct RgbdStageOptions {
  FrameReconstructionOptions reconstruction;  ///< decoder, triangulation, depth map
  RgbdColourOptions colour;                   ///< reference light, deblur, mapping, correction
  /// Acquisitions processed at once (≥ 1), each worker holding one acquisition's images and
  /// one FrameReconstructor per module it has met. Does not change the outputs.
  int threads = 1;
  /// Redo the stage from scratch (Workspace::BeginStage), even with other options recorded.
  bool force = false;
  /// Throws std::invalid_argument naming the option.
  void Check() const;
};

/// The options that decide the outputs, as workspace.json records them (compact JSON with
/// sorted keys): the decoder's, triangulation depth range and reprojection limit, outlier
/// rejection, max_edge_steps, and the colour pass's.
std::string RgbdOptionsJson(const RgbdStageOptions& options);

/// One acquisition over both passes.
struct RgbdAcquisitionSummary {
  int module = 0;
  int counter = 0;
  RgbdAcquisitionResult geometry;  ///< the geometry pass now (skipped: done before)
  RgbdAcquisitionResult colour;    ///< the colour pass now (skipped: done before)
  bool complete = false;           ///< its report exists after this run
  long long spots = 0;             ///< complete: from its report
  long long points = 0;
  std::vector<std::string> warnings;  ///< complete: its inputs' problems, from its report
  bool without_odometry = false;      ///< complete: not deblurred, no odometry at its time
  /// The failure of this acquisition (geometry's, else colour's), or null.
  const RgbdAcquisitionResult* Failure() const;
};

/// The stage's report (`WS/rgbd/report.json`, RgbdStageReportToJson): every acquisition of the
/// run, whether processed now or by an earlier run.
struct RgbdStageReport {
  std::string color_source;  ///< RgbdColorSource of the options it ran with
  int acquisitions = 0;      ///< in the run
  int done = 0;              ///< completed now
  int skipped = 0;           ///< completed by an earlier run (report present)
  int failed = 0;
  std::vector<RgbdAcquisitionSummary> results;  ///< ordered by (module, counter)
  std::vector<RgbdReferenceResult> references;  ///< one per module
  /// The modules' relative colour gains from their seams (rgbd_colour.hpp, RgbdSeamPass).
  ModuleGains module_gains;
  /// The colour (linear BGR) every module's median wall is mapped to (CommonWallColour).
  cv::Vec3d wall_colour_bgr{0, 0, 0};
  long long spots = 0;  ///< over every complete acquisition
  long long points = 0;
  double seconds = 0;  ///< the whole stage now, wall clock
  /// Mean and maximum per acquisition completed now (one worker's time, both passes).
  double seconds_per_acquisition = 0;
  double max_seconds_per_acquisition = 0;
  int threads = 1;
  /// Problems of the inputs that did not stop the stage (rgbd_inputs.hpp), one line each:
  /// pattern matrices, acquisitions redone because their images changed, repeated frames,
  /// blown-out or black textures.
  std::vector<std::string> warnings;
  /// The first failed acquisition in (module, counter) order; null when none failed.
  const RgbdAcquisitionResult* FirstFailure() const;
};

/// The report as JSON text (keys sorted; format in docs/rgbd.md).
std::string RgbdStageReportToJson(const RgbdStageReport& report);

/// Called after every item of a pass ("geometry", "colour": acquisitions; "reference":
/// modules), done, skipped or failed, never from two threads at once.
using StageProgress = std::function<void(const std::string& pass, int finished, int total)>;

/// Runs the RGB-D stage of `run` into `workspace` (records it there, workspace.hpp). Throws
/// std::invalid_argument on invalid options, WorkspaceConflict when the stage was recorded with
/// other options and !options.force, FileError when the rig cannot decode (a module's pattern
/// fails InferConstraints), does not match the images (CheckRigMatchesImages) or the workspace
/// cannot be written. Failures of single acquisitions (a missing, truncated or wrongly sized
/// image, a pattern that does not decode) are in the report, not thrown.
RgbdStageReport RunRgbdStage(const CaptureRun& run, Workspace& workspace,
                             const RgbdStageOptions& options, const StageProgress& progress = {});

}  // namespace sewer3d
