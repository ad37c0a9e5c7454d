#pragma once
/// \file
/// Camera calibration from views of a planar checkerboard (DESIGN.md, calibrate): pinhole +
/// 3-term radial model (the module file's camera model), initialised by Zhang's method and
/// refined by Ceres over the intrinsics and every view's pose (least squares on reprojection
/// error). Reports RMS, per-view RMS, per-corner residuals and the standard deviations of
/// the intrinsics from the estimate's covariance.

#include <Eigen/Core>
#include <vector>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/rigid3.hpp"

namespace sewer3d {

/// The board's inner corners in its own plane (z = 0), row-major: cols x rows corners of
/// pitch square_mm; point (i, j) = (j · square, i · square, 0).
std::vector<Eigen::Vector3d> BoardCorners(int cols, int rows, double square_mm);

struct CalibrationView {
  std::vector<Eigen::Vector2d> corners_px;  ///< detected, same order as BoardCorners
};

struct CalibrationResult {
  CameraIntrinsics intrinsics;
  std::vector<Rigid3d> camera_from_board;  ///< per view
  double rms_px = 0.0;
  std::vector<double> view_rms_px;
  std::vector<std::vector<Eigen::Vector2d>> residuals_px;  ///< observed − projected, per corner
  /// One standard deviation of fx, fy, cx, cy, k1, k2, k3 (scaled by the residual variance).
  std::array<double, 7> sigma{};
  int iterations = 0;
  bool converged = false;
  /// The views fix the intrinsics: the covariance exists and σ(fx) is below 5 % of fx. False
  /// for one pose repeated or boards that never tilt: a focal length from those is a guess.
  bool constrained = false;
};

/// Index of the view in `views` that `view` repeats (every corner within tolerance_px: the
/// same image twice, or a board that did not move), or -1.
int RepeatedView(const std::vector<CalibrationView>& views, const CalibrationView& view,
                 double tolerance_px = 0.5);

struct CalibrationOptions {
  bool fix_k3 = false;  ///< estimate only k1, k2
  int max_iterations = 200;
};

/// Needs at least 3 views with all corners; throws std::invalid_argument otherwise.
CalibrationResult CalibrateCamera(const std::vector<CalibrationView>& views,
                                  const std::vector<Eigen::Vector3d>& board, int image_width,
                                  int image_height, const CalibrationOptions& options = {});

}  // namespace sewer3d
