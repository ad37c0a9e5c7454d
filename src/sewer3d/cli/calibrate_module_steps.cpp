// `sewer3d calibrate module`'s inputs and its printed result: the pose folders, the nominal
// module, each pose's captures fed to the calibrator, and the summary of the estimate.

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/cli/calibrate_commands.hpp"
#include "sewer3d/cli/progress_bar.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/input_file.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/pattern/default_pattern.hpp"

namespace sewer3d::cli {

namespace fs = std::filesystem;

std::vector<fs::path> PoseFolders(const fs::path& captures) {
  std::vector<fs::path> poses;
  std::error_code ec;
  for (fs::directory_iterator it(captures, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    if (!fs::is_directory(p, ec)) continue;
    // The simulator's truth (it holds the pattern matrix it projected) is no pose.
    if (p.filename() == "truth" && IsRegularFile(p / "poses.json")) continue;
    const bool texture = IsRegularFile(p / "texture.png"),
               pattern = IsRegularFile(p / "pattern.png");
    if (texture && pattern) poses.push_back(p);
    if (texture != pattern)
      fmt::print("{}: {} without {}, skipped\n", p.string(),
                 texture ? "texture.png" : "pattern.png", texture ? "pattern.png" : "texture.png");
  }
  if (ec) throw FileError(captures, "cannot list the folder: " + ec.message());
  std::sort(poses.begin(), poses.end());
  return poses;
}

NominalModule LoadNominal(const std::string& nominal, const fs::path& first_image,
                          const cv::Size& size) {
  NominalModule n;
  if (!nominal.empty()) {
    LoadedModule loaded = LoadModule(nominal);
    n.module = loaded.module;
    n.pattern = loaded.pattern;
  } else {
    DefaultModuleOptions options;
    options.camera_width = size.width;
    options.camera_height = size.height;
    n.module = MakeDefaultModule(options);
    n.pattern = DefaultPatternArray();
  }
  if (size.width != n.module.camera.width || size.height != n.module.camera.height) {
    throw FileError(first_image,
                    fmt::format("image is {}x{}, the nominal module's camera {}x{}", size.width,
                                size.height, n.module.camera.width, n.module.camera.height));
  }
  // The nominal module's pattern must be one the decoder can use: its file is named if not.
  const auto infer = [&] { n.constraints = InferConstraints(n.pattern); };
  if (nominal.empty())
    infer();
  else
    ValidateFileContents(nominal, infer);
  return n;
}

CaptureTally AddCaptures(ModuleCalibrator& calibrator, const std::vector<fs::path>& poses,
                         const cv::Size& size, const std::string& board, bool quiet) {
  CaptureTally tally;
  std::vector<std::string>& used = tally.used;
  ProgressBar bar(quiet);
  for (const fs::path& pose : poses) {
    const cv::Mat texture = ReadImage(pose / "texture.png", cv::IMREAD_GRAYSCALE, kMaxCameraPixels);
    const cv::Mat pattern_image = ReadGreyImage(pose / "pattern.png");
    if (texture.size() != size || pattern_image.size() != size) {
      throw FileError(pose, "images differ in size from the first pose's");
    }
    const CaptureOutcome outcome = calibrator.AddCapture(texture, pattern_image);
    if (outcome.status == CaptureOutcome::Status::kBoardNotFound) {
      fmt::print("{}: {} board not found, skipped\n", pose.string(), board);
      continue;
    }
    if (outcome.status == CaptureOutcome::Status::kCornersNotCarried) {
      fmt::print("{}: {} of {} corners without enough decoded spots around them, skipped\n",
                 pose.string(), outcome.corners_missing, outcome.corners);
      continue;
    }
    if (outcome.status == CaptureOutcome::Status::kRepeated) {
      fmt::print("{}: the board lies where it did in {}, skipped\n", pose.string(),
                 used[static_cast<std::size_t>(outcome.repeats)]);
      ++tally.repeated;
      continue;
    }
    if (outcome.corners_missing > 0) {
      fmt::print("{}: {} of {} corners without enough decoded spots around them, used without\n",
                 pose.string(), outcome.corners_missing, outcome.corners);
    }
    used.push_back(pose.filename().string());
    bar.Update("calibrate module", static_cast<int>(used.size()), static_cast<int>(poses.size()),
               "poses");
  }
  return tally;
}

void PrintModuleCalibration(const ModuleCalibrationResult& r, const std::vector<std::string>& used,
                            std::size_t poses) {
  fmt::print(
      "calibrated module from {} of {} poses: camera RMS {:.4f} px, projector RMS {:.4f} px{}\n",
      used.size(), poses, r.camera_rms_px, r.projector_rms_px,
      r.converged ? "" : " (not converged)");
  fmt::print(
      "camera     fx {:.3f} ± {:.3f}  fy {:.3f} ± {:.3f}  cx {:.3f} ± {:.3f}  cy {:.3f} ± {:.3f}  "
      "k ({:.5f}, {:.5f}, {:.5f})\n",
      r.camera.fx, r.sigma[0], r.camera.fy, r.sigma[1], r.camera.cx, r.sigma[2], r.camera.cy,
      r.sigma[3], r.camera.k[0], r.camera.k[1], r.camera.k[2]);
  fmt::print(
      "projector  fx {:.3f} ± {:.3f}  fy {:.3f} ± {:.3f}  cx {:.3f} ± {:.3f}  cy {:.3f} ± {:.3f}  "
      "k ({:.5f}, {:.5f}, {:.5f})\n",
      r.projector.fx, r.sigma[4], r.projector.fy, r.sigma[5], r.projector.cx, r.sigma[6],
      r.projector.cy, r.sigma[7], r.projector.k[0], r.projector.k[1], r.projector.k[2]);
  const Eigen::Vector3d c = r.projector_from_camera.Inverse().translation;
  fmt::print(
      "extrinsics baseline {:.3f} ± {:.3f} mm, projector centre ({:.3f}, {:.3f}, {:.3f}) mm, "
      "rotation ± {:.4f} deg\n",
      c.norm(), r.sigma[8], c.x(), c.y(), c.z(), r.sigma[9]);
  for (size_t v = 0; v < used.size(); ++v) {
    fmt::print("  {}  camera {:.4f} px  projector {:.4f} px\n", used[v], r.view_camera_rms_px[v],
               r.view_projector_rms_px[v]);
  }  // Three views fix the focal lengths and centres, but not the lenses' distortion: a fit from
  // 3 of 6 simulated poses put the projector's k at (-0.125, 0.281, -0.433) for the true
  // (-0.08, 0.015, 0), and a plane at 140 mm then gave 161 of 731 spots.
  constexpr std::size_t kFewPoses = 6;
  if (used.size() < kFewPoses) {
    std::fflush(stdout);
    fmt::print(stderr,
               "sewer3d: warning: calibrated from {} poses only: fewer than {} leave the lens "
               "distortion (k) poorly determined; capture more poses, tilted differently\n",
               used.size(), kFewPoses);
  }
}

}  // namespace sewer3d::cli
