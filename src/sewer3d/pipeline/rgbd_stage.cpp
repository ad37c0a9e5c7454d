#include "sewer3d/pipeline/rgbd_stage.hpp"

#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/pattern/constraints.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;
constexpr const char* kStage = "rgbd";

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// One worker's reconstructors, built when the worker first meets a module: building one
// predicts the decoder's lattice and element centres, reused for every frame of that module.
class Reconstructors {
 public:
  Reconstructors(const CaptureRun& run, const std::vector<PatternConstraints>& constraints,
                 const FrameReconstructionOptions& options)
      : run_(run), constraints_(constraints), options_(options), built_(run.rig.modules.size()) {}

  FrameReconstructor& For(int module) {
    std::unique_ptr<FrameReconstructor>& r = built_.at(module);
    if (!r) {
      r = std::make_unique<FrameReconstructor>(
          run_.rig.modules[module].module, run_.patterns[module], constraints_[module], options_);
    }
    return *r;
  }

 private:
  const CaptureRun& run_;
  const std::vector<PatternConstraints>& constraints_;
  const FrameReconstructionOptions& options_;
  std::vector<std::unique_ptr<FrameReconstructor>> built_;
};

// The run's image file of `kind`; a missing index row becomes a failure naming the file the
// run's layout would have.
std::filesystem::path ImageFile(const CaptureRun& run, const Acquisition& a, ImageKind kind) {
  const int i = a.Image(kind);
  if (i >= 0) return run.folder / run.images[i].file;
  return run.folder / "images" / (ImageStem(a.module, a.counter, kind) + ".png");
}

cv::Mat ReadSized(const std::filesystem::path& file, const CameraIntrinsics& camera, int module,
                  bool colour) {
  cv::Mat image = colour ? ReadImage(file, cv::IMREAD_COLOR) : ReadGreyImage(file);
  if (image.cols != camera.width || image.rows != camera.height) {
    throw FileError(file, fmt::format("image is {}x{} but module m{}'s camera is {}x{}", image.cols,
                                      image.rows, module, camera.width, camera.height));
  }
  return image;
}

void Fail(RgbdAcquisitionResult& result, const std::filesystem::path& file,
          const std::string& message) {
  result.status = RgbdAcquisitionResult::Status::kFailed;
  result.file = file.string();
  // FileError's message is "PATH: problem"; the reason is the problem alone.
  const std::string prefix = result.file + ": ";
  result.reason = message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message;
}

RgbdAcquisitionResult ProcessAcquisition(const CaptureRun& run, const Acquisition& a,
                                         const std::filesystem::path& rgbd_folder,
                                         Reconstructors& reconstructors) {
  RgbdAcquisitionResult result;
  result.module = a.module;
  result.counter = a.counter;
  const RgbdFiles files = RgbdAcquisitionFiles(rgbd_folder, a.module, a.counter);
  if (RgbdAcquisitionDone(files)) {
    result.status = RgbdAcquisitionResult::Status::kSkipped;
    return result;
  }
  const auto start = Clock::now();
  const std::filesystem::path pattern_file = ImageFile(run, a, ImageKind::kPattern);
  const std::filesystem::path texture_file = ImageFile(run, a, ImageKind::kTextureBefore);
  for (const auto& [kind, file] : {std::pair{ImageKind::kPattern, pattern_file},
                                   std::pair{ImageKind::kTextureBefore, texture_file}}) {
    if (a.Image(kind) < 0) {
      Fail(result, file, std::string("no ") + ImageKindName(kind) + " image in acquisitions.csv");
      return result;
    }
  }
  const CameraIntrinsics& camera = run.rig.modules[a.module].module.camera;
  try {
    const cv::Mat pattern = ReadSized(pattern_file, camera, a.module, false);
    const cv::Mat3b texture = ReadSized(texture_file, camera, a.module, true);
    const FrameReconstruction frame = reconstructors.For(a.module).Reconstruct(pattern, &texture);
    const double reconstruct_seconds = SecondsSince(start);
    const json extra = {{"module", a.module},
                        {"counter", a.counter},
                        {"texture", texture_file.lexically_relative(run.folder).string()},
                        {"color", kRgbdColorSource},
                        {"seconds", {{"read_and_reconstruct", reconstruct_seconds}}}};
    WriteRgbdAcquisition(files, texture, frame,
                         pattern_file.lexically_relative(run.folder).string(), extra.dump());
    result.frame = frame.report;
  } catch (const FileError& e) {
    Fail(result, e.path(), e.what());
    return result;
  } catch (const std::invalid_argument& e) {  // the reconstructor refused the image
    Fail(result, pattern_file, e.what());
    return result;
  }
  result.seconds = SecondsSince(start);
  return result;
}

const char* StatusName(RgbdAcquisitionResult::Status status) {
  switch (status) {
    case RgbdAcquisitionResult::Status::kDone:
      return "done";
    case RgbdAcquisitionResult::Status::kSkipped:
      return "skipped";
    case RgbdAcquisitionResult::Status::kFailed:
      return "failed";
  }
  return "?";
}

}  // namespace

void RgbdStageOptions::Check() const {
  reconstruction.Check();
  SEWER3D_VALIDATE(threads >= 1, "threads", "must be at least 1, got " << threads);
}

std::string RgbdOptionsJson(const RgbdStageOptions& options) {
  const FrameReconstructionOptions& r = options.reconstruction;
  const json j = {{"max_edge_steps", r.max_edge_steps},
                  {"triangulation",
                   {{"z_min_mm", r.triangulation.z_min_mm},
                    {"z_max_mm", r.triangulation.z_max_mm},
                    {"max_reprojection_px", r.triangulation.max_reprojection_px}}},
                  {"outliers",
                   {{"radius_px", r.outliers.radius_px},
                    {"min_step_mm", r.outliers.min_step_mm},
                    {"fraction", r.outliers.fraction}}}};
  return j.dump();
}

const RgbdAcquisitionResult* RgbdStageReport::FirstFailure() const {
  for (const RgbdAcquisitionResult& r : results) {
    if (r.status == RgbdAcquisitionResult::Status::kFailed) return &r;
  }
  return nullptr;
}

std::string RgbdStageReportToJson(const RgbdStageReport& report) {
  json failures = json::array(), list = json::array();
  for (const RgbdAcquisitionResult& r : report.results) {
    json entry = {{"module", r.module}, {"counter", r.counter}, {"status", StatusName(r.status)}};
    if (r.status == RgbdAcquisitionResult::Status::kFailed) {
      failures.push_back(
          {{"module", r.module}, {"counter", r.counter}, {"file", r.file}, {"reason", r.reason}});
    } else if (r.status == RgbdAcquisitionResult::Status::kDone) {
      entry["spots"] = r.frame.spots_found;
      entry["points"] = r.frame.points;
      entry["seconds"] = r.seconds;
    }
    list.push_back(entry);
  }
  const json j = {{"stage", kStage},
                  {"color", kRgbdColorSource},
                  {"not_done_yet",
                   "colour and shading correction, motion deblur, texture -> 3D mapping at the "
                   "pattern instant (issue 14, items 3-5)"},
                  {"acquisitions", report.acquisitions},
                  {"done", report.done},
                  {"skipped", report.skipped},
                  {"failed", report.failed},
                  {"failures", failures},
                  {"totals", {{"spots", report.spots}, {"points", report.points}}},
                  {"seconds",
                   {{"stage", report.seconds},
                    {"per_acquisition_mean", report.seconds_per_acquisition},
                    {"per_acquisition_max", report.max_seconds_per_acquisition}}},
                  {"threads", report.threads},
                  {"per_acquisition", list}};
  return j.dump(2) + "\n";
}

RgbdStageReport RunRgbdStage(const CaptureRun& run, Workspace& workspace,
                             const RgbdStageOptions& options, const StageProgress& progress) {
  options.Check();
  SEWER3D_CHECK(
      run.patterns.size() == run.rig.modules.size(),
      "one pattern per module: " << run.patterns.size() << " for " << run.rig.modules.size());
  const auto start = Clock::now();
  std::vector<PatternConstraints> constraints;
  for (size_t k = 0; k < run.patterns.size(); ++k) {
    try {
      constraints.push_back(InferConstraints(run.patterns[k]));
    } catch (const std::invalid_argument& e) {
      throw FileError(run.folder / "rig.json", "module m" + std::to_string(k) +
                                                   ": cannot decode with its pattern: " + e.what());
    }
  }
  workspace.BeginStage(kStage, RgbdOptionsJson(options), options.force);
  const std::filesystem::path rgbd_folder = workspace.StageFolder(kStage);
  const std::vector<Acquisition> acquisitions = GroupAcquisitions(run.images);

  RgbdStageReport report;
  report.acquisitions = static_cast<int>(acquisitions.size());
  report.threads = options.threads;
  report.results.resize(acquisitions.size());
  std::mutex progress_mutex;
  int finished = 0;
  auto process = [&](size_t i, Reconstructors& reconstructors) {
    report.results[i] = ProcessAcquisition(run, acquisitions[i], rgbd_folder, reconstructors);
    const std::lock_guard lock(progress_mutex);
    ++finished;
    if (progress) progress(finished, report.acquisitions);
  };
  if (options.threads == 1) {
    Reconstructors reconstructors(run, constraints, options.reconstruction);
    for (size_t i = 0; i < acquisitions.size(); ++i) process(i, reconstructors);
  } else {
    tbb::enumerable_thread_specific<Reconstructors> per_worker(
        [&] { return Reconstructors(run, constraints, options.reconstruction); });
    tbb::task_arena arena(options.threads);
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, acquisitions.size(), 1),
                        [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t i = range.begin(); i != range.end(); ++i) {
                            // Isolated: a worker waiting inside a reconstruction never takes
                            // another acquisition, so it holds one acquisition's images.
                            tbb::this_task_arena::isolate([&] { process(i, per_worker.local()); });
                          }
                        });
    });
  }

  for (const RgbdAcquisitionResult& r : report.results) {
    switch (r.status) {
      case RgbdAcquisitionResult::Status::kDone:
        ++report.done;
        report.spots += r.frame.spots_found;
        report.points += r.frame.points;
        report.seconds_per_acquisition += r.seconds;
        report.max_seconds_per_acquisition =
            std::max(report.max_seconds_per_acquisition, r.seconds);
        break;
      case RgbdAcquisitionResult::Status::kSkipped:
        ++report.skipped;
        break;
      case RgbdAcquisitionResult::Status::kFailed:
        ++report.failed;
        break;
    }
  }
  if (report.done > 0) report.seconds_per_acquisition /= report.done;
  report.seconds = SecondsSince(start);
  WriteTextFileAtomically(rgbd_folder / "report.json", RgbdStageReportToJson(report));
  workspace.FinishStage(kStage, report.failed == 0,
                        {{"color", kRgbdColorSource},
                         {"acquisitions", std::to_string(report.acquisitions)},
                         {"failed", std::to_string(report.failed)}});
  return report;
}

}  // namespace sewer3d
