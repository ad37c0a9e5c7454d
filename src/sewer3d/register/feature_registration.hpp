#pragma once
/// \file
/// Feature-based pairwise registration (paper §4.3): SIFT keypoints on the two colour images,
/// matches by Lowe's ratio test and a cross check, lifted to 3-D by the depth maps (matches
/// without depth there, or on a depth step, are rejected), then RegisterPoints
/// (point_registration.hpp): RANSAC with the 3-point solver, Umeyama on the inliers,
/// Gauss–Newton on the Mahalanobis point-to-point cost with the depth noise model, and the
/// 6×6 information of b in a from the inlier geometry and that noise.

#include <opencv2/core.hpp>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/register/depth_geometry.hpp"
#include "sewer3d/register/point_registration.hpp"

namespace sewer3d {

struct FeatureRegistrationOptions {
  int max_keypoints = 0;  ///< per image, strongest first; 0: all
  /// SIFT's contrast threshold (OpenCV default 0.04); lower keeps the faint texture of
  /// sewer walls.
  double contrast_threshold = 0.02;
  double ratio = 0.8;       ///< Lowe's ratio: best / second-best descriptor distance below it
  bool cross_check = true;  ///< keep a match only if it is also b's best match in a
  /// Wider images are detected on an area-averaged copy this wide (keypoints scaled back, their
  /// localisation σ scaled up with them): SIFT and brute-force matching on the full 2592 px
  /// frame take ~14 s a pair; 0: always the full image.
  int max_detect_width_px = 1300;
  /// Depth at a keypoint is bilinear over the 4 pixels around it; rejected if they spread
  /// over more than this (a depth step or an edge of the map).
  double max_depth_spread_mm = 0.5;
  DepthNoiseModel noise;
  PointRegistrationOptions points;

  void Check() const;
};

struct FeatureRegistrationReport {
  int keypoints_a = 0, keypoints_b = 0;  ///< inside each depth map's valid area
  int matches = 0;                       ///< after the ratio test and the cross check
  int with_depth = 0;                    ///< lifted to 3-D in both images
  int ransac_inliers = 0;
  int inliers = 0;  ///< after refinement and re-selection
  int ransac_iterations = 0;
  double variance_factor = 0.0;  ///< PointRegistrationResult::variance_factor
};

struct FeatureRegistrationResult {
  bool converged = false;
  Rigid3d a_from_b;  ///< pose of b's camera in a's camera frame
  /// Information of the pose-graph residual [translation; 2 vec(rotation error)] (mm, rad).
  Matrix6d information = Matrix6d::Zero();
  int inliers = 0;
  double rms_mm = 0.0;  ///< 3-D distance of the inlier matches after registration
  FeatureRegistrationReport report;
};

/// Registers b onto a. Expected failures (too few features, matches or inliers) give
/// converged = false with the report filled so far; throws std::invalid_argument for bad
/// options or images whose sizes do not match their cameras.
FeatureRegistrationResult RegisterFeatures(const RgbdImage& a, const CameraModel& camera_a,
                                           const RgbdImage& b, const CameraModel& camera_b,
                                           const FeatureRegistrationOptions& options);

}  // namespace sewer3d
