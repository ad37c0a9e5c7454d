// `sewer3d calibrate module`: camera, projector and their extrinsics from checkerboard
// captures (docs/calibration.md).

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "sewer3d/calib/module_from_captures.hpp"
#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/cli/calibrate_commands.hpp"
#include "sewer3d/cli/progress_bar.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/input_file.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/pattern/constraints.hpp"
#include "sewer3d/pattern/default_pattern.hpp"

namespace sewer3d::cli {
namespace {

namespace fs = std::filesystem;

struct ModuleArgs {
  std::string captures, board = "9x6", out, nominal;
  double square_mm = 10.0;
  bool quiet = false;
};

// The pose folders below `captures` that hold texture.png and pattern.png, sorted; a folder
// with only one of the two is named as skipped.
std::vector<fs::path> PoseFolders(const fs::path& captures) {
  std::vector<fs::path> poses;
  std::error_code ec;
  for (fs::directory_iterator it(captures, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    if (!fs::is_directory(p, ec)) continue;
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

// The nominal (design) module: pattern, projector size, and a geometry close enough to predict
// the lattice and pick the pattern tile; the default module at the images' size without one.
struct Nominal {
  ModuleDescription module;
  BinaryArray pattern;
  PatternConstraints constraints;
};

Nominal LoadNominal(const ModuleArgs& a, const fs::path& first_image, const cv::Size& size) {
  Nominal n;
  if (!a.nominal.empty()) {
    LoadedModule loaded = LoadModule(a.nominal);
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
  if (a.nominal.empty())
    infer();
  else
    ValidateFileContents(a.nominal, infer);
  return n;
}

// Adds every pose's captures; returns the names of the poses used (the others are reported).
std::vector<std::string> AddCaptures(ModuleCalibrator& calibrator,
                                     const std::vector<fs::path>& poses, const cv::Size& size,
                                     const ModuleArgs& a) {
  std::vector<std::string> used;
  ProgressBar bar(a.quiet);
  for (const fs::path& pose : poses) {
    const cv::Mat texture = ReadImage(pose / "texture.png", cv::IMREAD_GRAYSCALE, kMaxCameraPixels);
    const cv::Mat pattern_image = ReadGreyImage(pose / "pattern.png");
    if (texture.size() != size || pattern_image.size() != size) {
      throw FileError(pose, "images differ in size from the first pose's");
    }
    const CaptureOutcome outcome = calibrator.AddCapture(texture, pattern_image);
    if (outcome.status == CaptureOutcome::Status::kBoardNotFound) {
      fmt::print("{}: {} board not found, skipped\n", pose.string(), a.board);
      continue;
    }
    if (outcome.status == CaptureOutcome::Status::kCornersNotCarried) {
      fmt::print("{}: {} of {} corners without enough decoded spots around them, skipped\n",
                 pose.string(), outcome.corners_missing, outcome.corners);
      continue;
    }
    used.push_back(pose.filename().string());
    bar.Update("calibrate module", static_cast<int>(used.size()), static_cast<int>(poses.size()),
               "poses");
  }
  return used;
}

void PrintCalibration(const ModuleCalibrationResult& r, const std::vector<std::string>& used,
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
  }
}

int RunModule(const ModuleArgs& a) {
  const auto board_size = ParseSize(a.board);
  CheckOutputFile(a.out);  // before minutes of work
  // pattern.png is written beside the module file: they must be two files.
  if (fs::path(a.out).filename() == "pattern.png")
    throw InvalidValue("--out", "names the module file (JSON), got " + a.out +
                                    ": pattern.png is written beside it");
  CheckOutputFile(fs::path(a.out).parent_path() / "pattern.png");
  const std::vector<fs::path> poses = PoseFolders(a.captures);
  if (poses.size() < 3) {
    throw FileError(
        a.captures,
        fmt::format("{} pose folders with texture.png and pattern.png; calibration needs at "
                    "least 3 (layout: docs/calibration.md)",
                    poses.size()));
  }
  const fs::path first_image = poses[0] / "texture.png";
  const cv::Size size = ReadImage(first_image, cv::IMREAD_GRAYSCALE, kMaxCameraPixels).size();
  const Nominal nominal = LoadNominal(a, first_image, size);
  BoardLayout board_layout;
  board_layout.cols = board_size->first;
  board_layout.rows = board_size->second;
  board_layout.square_mm = a.square_mm;
  ModuleCalibrator calibrator(nominal.module, nominal.pattern, nominal.constraints, board_layout);
  const std::vector<std::string> used = AddCaptures(calibrator, poses, size, a);
  if (used.size() < 3) {
    fmt::print(stderr,
               "sewer3d: error: {} of {} poses usable; module calibration needs at least 3\n",
               used.size(), poses.size());
    return 1;
  }
  ModuleFromCapturesResult calibrated;
  try {
    calibrated = calibrator.Calibrate();
  } catch (const std::invalid_argument& e) {
    // The estimate left the valid range: the captures do not fix the module.
    fmt::print(stderr,
               "sewer3d: error: calibration failed: the estimate is not a valid module ({}); "
               "check that each pose's texture and pattern images belong together\n",
               e.what());
    return 1;
  }
  ModuleDescription module = calibrated.module;
  try {
    module.Check();
  } catch (const InvalidValue& e) {
    // Every length of the estimate scales with the board's square: a baseline out of range
    // is a wrong --square-mm far more often than a wrong module.
    if (e.field().rfind("projector_from_camera", 0) != 0) throw;
    throw InvalidValue("--square-mm", fmt::format("{:g} mm makes the calibrated module's {}: "
                                                  "{}; is it the board's square size?",
                                                  a.square_mm, e.field(), e.problem()));
  }
  module.pattern.matrix_path = "pattern.png";
  module.source_json.clear();
  SaveModule(a.out, module);
  WritePatternMatrix(fs::path(a.out).parent_path() / "pattern.png", nominal.pattern);
  PrintCalibration(calibrated.second_pass, used, poses.size());
  fmt::print("wrote {} and pattern.png beside it\n", a.out);
  return 0;
}

}  // namespace

Command AddCalibrateModuleCommand(CLI::App& calibrate) {
  auto args = std::make_shared<ModuleArgs>();
  CLI::App* sub = calibrate.add_subcommand(
      "module", "Camera, projector and their extrinsics from checkerboard captures");
  sub->add_option("--captures", args->captures,
                  "Folder of pose folders (pose_NN/texture.png, pattern.png)")
      ->required()
      ->check(CLI::ExistingDirectory);
  AddBoardOption(*sub, args->board);
  AddSquareOption(*sub, args->square_mm);
  sub->add_option("--out", args->out, "Calibrated module.json (pattern.png is written beside it)")
      ->required();
  sub->add_option(
         "--nominal", args->nominal,
         "Design module (pattern, projector size, rough geometry); default: the default module")
      ->check(CLI::ExistingFile);
  sub->add_flag("--quiet", args->quiet, "No progress bar");
  return {sub, [args] { return RunModule(*args); }};
}

}  // namespace sewer3d::cli
