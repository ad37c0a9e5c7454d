#pragma once
/// \file
/// Files of a camera calibration: the result JSON and, per image, a picture of the detected
/// corners coloured by reprojection error. Errors are FileError.

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sewer3d/calib/camera_calibration.hpp"
#include "sewer3d/calib/module_from_captures.hpp"
#include "sewer3d/camera/module.hpp"

namespace sewer3d {

struct CameraCalibrationFile {
  CalibrationResult result;
  std::vector<std::string> images;   ///< used, in the order of result's views
  std::vector<std::string> skipped;  ///< board not found
  int board_cols = 0, board_rows = 0;
  double square_mm = 0.0;
};

/// camera.json: {"camera": {module.json camera fields}, "rms_px", "sigma": {...},
/// "views": [{"image", "rms_px"}], "skipped": [...], "board": {...}, "iterations", "converged"}.
void WriteCameraCalibration(const std::filesystem::path& path, const CameraCalibrationFile& file);

/// The image with each corner drawn as a disk coloured from green (0) to red (≥ 3 × rms_px)
/// and its residual as a line 20× enlarged.
void WriteCornerErrorImage(const std::filesystem::path& path, const cv::Mat& grey,
                           const std::vector<Eigen::Vector2d>& corners,
                           const std::vector<Eigen::Vector2d>& residuals, double rms_px);

/// The module file `calibrate module` writes carries its calibration in an extra member (the
/// module contract keeps such members): {"calibration": {"poses_used", "poses", "rms_px":
/// {"camera", "projector"}, "sigma": {"camera": {fx, fy, cx, cy}, "projector": {…},
/// "baseline_mm", "rotation_deg"}}}, one standard deviation each. Returns that object as JSON
/// text, to be the written module's source_json.
std::string ModuleCalibrationMember(const ModuleCalibrationResult& r, int poses_used, int poses);

/// ModuleCalibrationResult::sigma from the "calibration" member of a loaded module
/// (module.source_json, the text LoadModule read from `module_file`, which messages name;
/// FileError where it is malformed); nullopt when the module has none (not from `calibrate
/// module`).
std::optional<std::array<double, 10>> ModuleCalibrationSigma(
    const ModuleDescription& module, const std::filesystem::path& module_file);

/// A captures folder's board.json (`simulate calibration` writes one): cols, rows and
/// square_mm, each member it lacks taken from `fallback`.
BoardLayout ReadBoardLayout(const std::filesystem::path& file, const BoardLayout& fallback);

}  // namespace sewer3d
