#pragma once
/// \file
/// Module calibration (DESIGN.md, calibrate): checkerboard corners carried into the projector
/// by local homographies fitted to decoded spots (Moreno & Taubin 2012), the projector
/// calibrated as an inverse camera, then camera, projector and projector_from_camera
/// optimised together (stereo) on both sets of corners.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/rigid3.hpp"

namespace sewer3d {

struct CornerTransferOptions {
  double radius_px = 90.0;  ///< decoded spots used around each corner (camera px)
  int min_spots = 12;       ///< fewer: the corner is not transferred
  double ransac_px = 1.0;   ///< inlier threshold of the homography, projector px
  /// When both are set, the homography is fitted between undistorted normalised coordinates,
  /// where a plane's image map is exactly one (Moreno & Taubin fit in pixels, where lens
  /// distortion bends it); a second pass with the first calibration's models uses this.
  std::optional<CameraIntrinsics> camera, projector;
};

/// Projector pixel of each camera corner: homography camera → projector fitted by RANSAC to
/// the decoded spots (camera px, projector element centre px) near the corner; nullopt where
/// too few spots or inliers.
std::vector<std::optional<Eigen::Vector2d>> CornersInProjector(
    const std::vector<Eigen::Vector2d>& corners, const std::vector<Eigen::Vector2d>& spot_camera_px,
    const std::vector<Eigen::Vector2d>& spot_projector_px,
    const CornerTransferOptions& options = {});

struct ModuleCalibrationView {
  std::vector<Eigen::Vector2d> camera_corners;  ///< every board corner
  /// Every board corner; NaN where it could not be carried into the projector (too few
  /// decoded spots around it): the view then counts for the camera and for the corners that
  /// were carried.
  std::vector<Eigen::Vector2d> projector_corners;
  bool Complete() const;  ///< every projector corner carried
};

/// One view's decoded spots: camera pixel and projector element centre of each.
struct SpotCorrespondences {
  std::vector<Eigen::Vector2d> camera_px, projector_px;
};

struct ModuleCalibrationResult {
  CameraIntrinsics camera, projector;
  Rigid3d projector_from_camera;
  double camera_rms_px = 0.0, projector_rms_px = 0.0;
  std::vector<double> view_camera_rms_px, view_projector_rms_px;
  /// One standard deviation: camera fx fy cx cy, projector fx fy cx cy, baseline (mm),
  /// extrinsic rotation (deg, largest axis).
  std::array<double, 10> sigma{};
  int iterations = 0;
  bool converged = false;
};

/// Needs at least 3 views with every projector corner (the projector's own start); throws
/// std::invalid_argument otherwise. The others join the joint refinement with their corners.
ModuleCalibrationResult CalibrateModule(const std::vector<ModuleCalibrationView>& views,
                                        const std::vector<Eigen::Vector3d>& board, int camera_width,
                                        int camera_height, int projector_width,
                                        int projector_height);

/// Second pass of the corner transfer: every view's corners carried again with the lens
/// models of `camera` and `projector` (homographies fitted in undistorted coordinates). A
/// corner that cannot be carried now keeps what it had. Returns the number of views whose
/// every carried corner was carried again.
int RetransferCorners(std::vector<ModuleCalibrationView>& views,
                      const std::vector<SpotCorrespondences>& spots, const CameraIntrinsics& camera,
                      const CameraIntrinsics& projector, const CornerTransferOptions& options = {});

}  // namespace sewer3d
