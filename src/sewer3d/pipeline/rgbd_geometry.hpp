#pragma once
/// \file
/// The RGB-D stage's geometry pass over one acquisition: decode and triangulate the pattern
/// image with its module's FrameReconstructor and write the depth map, its preview, the cloud
/// (without colour: the colour pass colours it) and the geometry report (io/rgbd_io.hpp).

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "sewer3d/pattern/constraints.hpp"
#include "sewer3d/run/capture_run.hpp"
#include "sewer3d/triangulate/reconstruct_frame.hpp"

namespace sewer3d {

/// What happened to one acquisition in one pass.
struct RgbdAcquisitionResult {
  enum class Status { kDone, kSkipped, kFailed };
  int module = 0;
  int counter = 0;
  Status status = Status::kDone;
  std::string file;    ///< kFailed: the file at fault (as the run names it, or the output)
  std::string reason;  ///< kFailed: one line
  FrameReport frame;   ///< geometry pass, kDone: spots, points, rejections, stage times
  double seconds = 0;  ///< kDone: reading, processing and writing
  /// kDone: problems of its inputs that did not stop it (rgbd_inputs.hpp), one line each.
  std::vector<std::string> warnings;
};

/// Marks `result` failed at `file`; `message` may start with "file: " (FileError), which is
/// dropped from the reason.
void FailAcquisition(RgbdAcquisitionResult& result, const std::filesystem::path& file,
                     const std::string& message);

/// One worker's reconstructors, built when the worker first meets a module: building one
/// predicts the decoder's lattice and element centres, reused for every frame of that module.
class Reconstructors {
 public:
  Reconstructors(const CaptureRun& run, const std::vector<PatternConstraints>& constraints,
                 const FrameReconstructionOptions& options);
  FrameReconstructor& For(int module);

 private:
  const CaptureRun* run_;
  const std::vector<PatternConstraints>* constraints_;
  const FrameReconstructionOptions* options_;
  std::vector<std::shared_ptr<FrameReconstructor>> built_;
};

/// The geometry pass of acquisition `a` into `rgbd_folder` (`WS/rgbd`): skipped when its
/// geometry report exists. Bad images fail the acquisition (in the result), never throw.
RgbdAcquisitionResult RgbdGeometryPass(const CaptureRun& run, const Acquisition& a,
                                       const std::filesystem::path& rgbd_folder,
                                       Reconstructors& reconstructors);

}  // namespace sewer3d
