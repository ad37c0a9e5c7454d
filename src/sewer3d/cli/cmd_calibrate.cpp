// `sewer3d calibrate camera`: intrinsics of a camera from checkerboard images.

#include <fmt/core.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "sewer3d/calib/camera_calibration.hpp"
#include "sewer3d/calib/chessboard.hpp"
#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/calibrate_commands.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/calibration_io.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/input_file.hpp"
#include "sewer3d/io/text_file.hpp"

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
  CheckFileNotInRunOrWorkspace(a.out, "--out");
  CheckOutputFile(a.out);
  CheckNotAModuleFile(a.out, "--out", "a camera calibration");
  for (const std::string& image : a.images) CheckNotAnInput(a.out, image, "--images");
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
               "calibration needs at least 3{}\n",
               views.size(), a.images.size(),
               views.empty() ? " (--board counts inner corners: 10 x 7 squares is 9x6)" : "");
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
  AddBoardOption(*camera, args->board);
  AddSquareOption(*camera, args->square_mm);
  camera->add_option("--out", args->out, "Result JSON (camera.json)")
      ->required()
      ->check(FileNameEnding(".json", "the calibration is written as JSON text"));
  camera->add_flag("--no-pictures", args->no_pictures,
                   "Do not write the per-image corner pictures");
  const Command module = AddCalibrateModuleCommand(*sub);
  return {sub, [args, camera, module] {
            if (module.app->parsed()) return module.run();
            return camera->parsed() ? RunCamera(*args) : 2;
          }};
}

}  // namespace sewer3d::cli
