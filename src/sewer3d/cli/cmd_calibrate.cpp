// `sewer3d calibrate camera`: intrinsics of a camera from checkerboard images.

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "sewer3d/calib/camera_calibration.hpp"
#include "sewer3d/calib/chessboard.hpp"
#include "sewer3d/calib/module_from_captures.hpp"
#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/io/calibration_io.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/pattern/constraints.hpp"
#include "sewer3d/pattern/default_pattern.hpp"

namespace sewer3d::cli {
namespace {

struct CameraArgs {
  std::vector<std::string> images;
  std::string board = "9x6", out;
  double square_mm = 25.0;
  bool no_pictures = false;
};

int RunCamera(const CameraArgs& a) {
  const auto board_size = ParseSize(a.board);
  CameraCalibrationFile file;
  file.board_cols = board_size->first;
  file.board_rows = board_size->second;
  file.square_mm = a.square_mm;
  const auto board = BoardCorners(file.board_cols, file.board_rows, a.square_mm);
  std::vector<CalibrationView> views;
  std::vector<cv::Mat> greys;
  cv::Size size;
  for (const std::string& path : a.images) {
    const cv::Mat grey = ReadImage(path, cv::IMREAD_GRAYSCALE, kMaxCameraPixels);
    if (size.empty()) size = grey.size();
    if (grey.size() != size) {
      throw FileError(path,
                      fmt::format("image is {}x{}, the first image {}x{}: one camera, one size",
                                  grey.cols, grey.rows, size.width, size.height));
    }
    const auto corners = DetectChessboard(grey, file.board_cols, file.board_rows);
    if (!corners) {
      fmt::print("{}: {} board not found, skipped\n", path, a.board);
      file.skipped.push_back(path);
      continue;
    }
    if (const int same = RepeatedView(views, {*corners}); same >= 0) {
      fmt::print("{}: the board lies where it did in {}, skipped\n", path, file.images[same]);
      file.skipped.push_back(path);
      continue;
    }
    views.push_back({*corners});
    greys.push_back(grey);
    file.images.push_back(path);
  }
  if (views.size() < 3) {
    fmt::print(stderr,
               "sewer3d: error: the board was found in {} distinct poses of {} images; "
               "calibration needs at least 3\n",
               views.size(), a.images.size());
    return 1;
  }
  file.result = CalibrateCamera(views, board, size.width, size.height);
  const CalibrationResult& r = file.result;
  if (!r.constrained) {
    fmt::print(stderr,
               "sewer3d: error: the {} views do not fix the focal length (σ fx {:.3g} px of "
               "{:.1f}); show the board tilted in different directions\n",
               views.size(), r.sigma[0], r.intrinsics.fx);
    return 1;
  }
  WriteCameraCalibration(a.out, file);
  const std::filesystem::path folder = std::filesystem::path(a.out).parent_path();
  if (!a.no_pictures) {
    // Named after the image; after its folder and the image when names repeat (pose_00/texture.png,
    // …).
    std::set<std::string> stems;
    bool repeated = false;
    for (const std::string& image : file.images)
      repeated |= !stems.insert(std::filesystem::path(image).stem().string()).second;
    for (size_t v = 0; v < views.size(); ++v) {
      const std::filesystem::path image(file.images[v]);
      const std::string name =
          repeated ? image.parent_path().filename().string() + "_" + image.stem().string()
                   : image.stem().string();
      const auto picture = folder / (name + "_corners.png");
      WriteCornerErrorImage(picture, greys[v], views[v].corners_px, r.residuals_px[v], r.rms_px);
    }
  }
  const CameraIntrinsics& c = r.intrinsics;
  fmt::print("calibrated {}x{} camera from {} of {} images ({} corners each): RMS {:.4f} px{}\n",
             c.width, c.height, views.size(), a.images.size(), board.size(), r.rms_px,
             r.converged ? "" : " (not converged)");
  fmt::print("fx {:.3f} ± {:.3f}  fy {:.3f} ± {:.3f}  cx {:.3f} ± {:.3f}  cy {:.3f} ± {:.3f} px\n",
             c.fx, r.sigma[0], c.fy, r.sigma[1], c.cx, r.sigma[2], c.cy, r.sigma[3]);
  fmt::print("k  {:.5f} ± {:.5f}, {:.5f} ± {:.5f}, {:.5f} ± {:.5f}\n", c.k[0], r.sigma[4], c.k[1],
             r.sigma[5], c.k[2], r.sigma[6]);
  for (size_t v = 0; v < views.size(); ++v)
    fmt::print("  {:.4f} px  {}\n", r.view_rms_px[v], file.images[v]);
  fmt::print("wrote {}{}\n", a.out,
             a.no_pictures ? "" : " and a <image>_corners.png per image beside it");
  return 0;
}

struct ModuleArgs {
  std::string captures, board = "9x6", out, nominal;
  double square_mm = 10.0;
};

int RunModule(const ModuleArgs& a) {
  namespace fs = std::filesystem;
  const auto board_size = ParseSize(a.board);
  std::vector<fs::path> poses;
  for (const auto& entry : fs::directory_iterator(a.captures)) {
    if (entry.is_directory() && fs::exists(entry.path() / "texture.png") &&
        fs::exists(entry.path() / "pattern.png")) {
      poses.push_back(entry.path());
    }
  }
  std::sort(poses.begin(), poses.end());
  if (poses.size() < 3) {
    throw FileError(
        a.captures,
        fmt::format("{} pose folders with texture.png and pattern.png; calibration needs at "
                    "least 3 (layout: docs/calibration.md)",
                    poses.size()));
  }
  // The nominal (design) module: pattern, projector size, and a geometry close enough to
  // predict the lattice and pick the pattern tile.
  ModuleDescription nominal;
  BinaryArray pattern;
  const cv::Mat first = ReadImage(poses[0] / "texture.png", cv::IMREAD_GRAYSCALE, kMaxCameraPixels);
  if (!a.nominal.empty()) {
    LoadedModule loaded = LoadModule(a.nominal);
    nominal = loaded.module;
    pattern = loaded.pattern;
  } else {
    DefaultModuleOptions options;
    options.camera_width = first.cols;
    options.camera_height = first.rows;
    nominal = MakeDefaultModule(options);
    pattern = DefaultPatternArray();
  }
  if (first.cols != nominal.camera.width || first.rows != nominal.camera.height) {
    throw FileError(poses[0] / "texture.png",
                    fmt::format("image is {}x{}, the nominal module's camera {}x{}", first.cols,
                                first.rows, nominal.camera.width, nominal.camera.height));
  }
  BoardLayout board_layout;
  board_layout.cols = board_size->first;
  board_layout.rows = board_size->second;
  board_layout.square_mm = a.square_mm;
  ModuleCalibrator calibrator(nominal, pattern, InferConstraints(pattern), board_layout);
  std::vector<std::string> used;
  for (const fs::path& pose : poses) {
    const cv::Mat texture = ReadImage(pose / "texture.png", cv::IMREAD_GRAYSCALE, kMaxCameraPixels);
    const cv::Mat pattern_image = ReadGreyImage(pose / "pattern.png");
    if (texture.size() != first.size() || pattern_image.size() != first.size()) {
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
    fmt::print(stderr, "\rcalibrate module: {} of {} poses read ", used.size(), poses.size());
  }
  fmt::print(stderr, "\n");
  if (used.size() < 3) {
    fmt::print(stderr,
               "sewer3d: error: {} of {} poses usable; module calibration needs at least 3\n",
               used.size(), poses.size());
    return 1;
  }
  const ModuleFromCapturesResult calibrated = calibrator.Calibrate();
  const ModuleCalibrationResult& r = calibrated.second_pass;
  ModuleDescription module = calibrated.module;
  module.pattern.matrix_path = "pattern.png";
  module.source_json.clear();
  SaveModule(a.out, module);
  WritePatternMatrix(fs::path(a.out).parent_path() / "pattern.png", pattern);
  fmt::print(
      "calibrated module from {} of {} poses: camera RMS {:.4f} px, projector RMS {:.4f} px{}\n",
      used.size(), poses.size(), r.camera_rms_px, r.projector_rms_px,
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
  fmt::print("wrote {} and pattern.png beside it\n", a.out);
  return 0;
}

}  // namespace

Command AddCalibrateCommand(CLI::App& app) {
  auto args = std::make_shared<CameraArgs>();
  CLI::App* sub =
      app.add_subcommand("calibrate", "Calibrate cameras and modules from checkerboard images");
  sub->require_subcommand(1);
  CLI::App* camera = sub->add_subcommand(
      "camera", "Camera intrinsics (pinhole + 3-term radial) from checkerboard images");
  camera->add_option("--images", args->images, "Checkerboard images (one camera, one size)")
      ->required()
      ->check(CLI::ExistingFile);
  camera->add_option("--board", args->board, "Inner corners COLSxROWS")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& s) {
            const auto size = ParseSize(s);
            return size && size->first >= 3 && size->second >= 3
                       ? std::string()
                       : "expected COLSxROWS, at least 3x3 inner corners, got " + s;
          },
          "COLSxROWS"));
  camera->add_option("--square-mm", args->square_mm, "Square size")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  camera->add_option("--out", args->out, "Result JSON (camera.json)")->required();
  camera->add_flag("--no-pictures", args->no_pictures,
                   "Do not write the per-image corner pictures");
  auto module_args = std::make_shared<ModuleArgs>();
  CLI::App* module = sub->add_subcommand(
      "module", "Camera, projector and their extrinsics from checkerboard captures");
  module
      ->add_option("--captures", module_args->captures,
                   "Folder of pose folders (pose_NN/texture.png, pattern.png)")
      ->required()
      ->check(CLI::ExistingDirectory);
  module->add_option("--board", module_args->board, "Inner corners COLSxROWS")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& s) {
            const auto size = ParseSize(s);
            return size && size->first >= 3 && size->second >= 3
                       ? std::string()
                       : "expected COLSxROWS, at least 3x3 inner corners, got " + s;
          },
          "COLSxROWS"));
  module->add_option("--square-mm", module_args->square_mm, "Square size")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  module
      ->add_option("--out", module_args->out,
                   "Calibrated module.json (pattern.png is written beside it)")
      ->required();
  module
      ->add_option(
          "--nominal", module_args->nominal,
          "Design module (pattern, projector size, rough geometry); default: the default module")
      ->check(CLI::ExistingFile);
  return {sub, [args, camera, module_args, module] {
            if (module->parsed()) return RunModule(*module_args);
            return camera->parsed() ? RunCamera(*args) : 2;
          }};
}

}  // namespace sewer3d::cli
