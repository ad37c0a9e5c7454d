#include "sewer3d/pipeline/rgbd_geometry.hpp"

#include <fmt/core.h>

#include <chrono>
#include <nlohmann/json.hpp>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/pipeline/acquisition_images.hpp"
#include "sewer3d/pipeline/rgbd_inputs.hpp"

namespace sewer3d {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

void FailAcquisition(RgbdAcquisitionResult& result, const std::filesystem::path& file,
                     const std::string& message) {
  result.status = RgbdAcquisitionResult::Status::kFailed;
  result.file = file.string();
  const std::string prefix = result.file + ": ";
  result.reason = message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message;
}

Reconstructors::Reconstructors(const CaptureRun& run,
                               const std::vector<PatternConstraints>& constraints,
                               const FrameReconstructionOptions& options)
    : run_(&run), constraints_(&constraints), options_(&options), built_(run.rig.modules.size()) {}

FrameReconstructor& Reconstructors::For(int module) {
  std::shared_ptr<FrameReconstructor>& r = built_.at(module);
  if (!r) {
    r = std::make_shared<FrameReconstructor>(run_->rig.modules[module].module,
                                             run_->patterns[module], (*constraints_)[module],
                                             *options_);
  }
  return *r;
}

RgbdAcquisitionResult RgbdGeometryPass(const CaptureRun& run, const Acquisition& a,
                                       const std::filesystem::path& rgbd_folder,
                                       Reconstructors& reconstructors) {
  RgbdAcquisitionResult result;
  result.module = a.module;
  result.counter = a.counter;
  const RgbdFiles files = RgbdAcquisitionFiles(rgbd_folder, a.module, a.counter);
  if (RgbdGeometryDone(files)) {
    result.status = RgbdAcquisitionResult::Status::kSkipped;
    return result;
  }
  const auto start = Clock::now();
  const std::filesystem::path pattern_file = AcquisitionImageFile(run, a, ImageKind::kPattern);
  try {
    // No texture here: the colour pass colours the cloud from the corrected image.
    const FrameReconstruction frame =
        reconstructors.For(a.module).Reconstruct(ReadPatternImage(run, a));
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (frame.report.points == 0) {
      result.warnings.push_back(fmt::format(
          "{}: no depth: {}; its texture is placed by the pipe prior alone", pattern_file.string(),
          frame.report.spots_decoded == 0
              ? fmt::format("{} spots found, none decoded (a blank, blown-out or foreign "
                            "pattern image?)",
                            frame.report.spots_found)
              : NoPointsReason(frame.report)));
    } else if (const std::string doubt = FrameDoubt(frame.report, frame.points.size());
               !doubt.empty()) {
      result.warnings.push_back(pattern_file.string() + ": doubtful depth: " + doubt);
    }
    const nlohmann::json extra = {{"module", a.module},
                                  {"counter", a.counter},
                                  {"inputs", InputStamps(run, a)},
                                  {"warnings", result.warnings},
                                  {"seconds", {{"read_and_reconstruct", seconds}}}};
    if (frame.report.not_of_module) {
      FailAcquisition(result, pattern_file, NotOfModuleReason(frame.report));
      return result;
    }
    WriteRgbdGeometry(files, frame, pattern_file.lexically_relative(run.folder).string(),
                      extra.dump());
    result.frame = frame.report;
  } catch (const FileError& e) {
    FailAcquisition(result, e.path(), e.what());
    return result;
  } catch (const std::invalid_argument& e) {  // the reconstructor refused the image
    FailAcquisition(result, pattern_file, e.what());
    return result;
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace sewer3d
