#pragma once
/// \file
/// Colour at the pattern instant (paper §3.2, issue 14 item 5). An acquisition is a triplet
/// texture_before → pattern → texture_after a few ms apart while the robot moves, so the texture
/// images see the wall from slightly different poses than the pattern image whose depth map
/// they must colour. The camera's motion after_from_before is measured from AKAZE matches of the
/// two texture images (before-features lifted to 3-D by the pattern's depth, PnP RANSAC on
/// undistorted normalised points, then Levenberg–Marquardt refinement), the pose at the
/// pattern's time is interpolated (slerp + lerp), and each pixel's 3-D point at the pattern
/// instant is projected into both texture images and their bilinear samples blended by time.
/// With too few matches (plastic pipe), the caller's odometry gives the motion instead; without
/// odometry the texture is used as it is. The report says which.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/rigid3.hpp"

namespace sewer3d {

/// Capture times (s, any common origin) of the three images of an acquisition.
struct TripletTimes {
  double before_s = 0.0;
  double pattern_s = 0.005;
  double after_s = 0.010;

  /// Throws InvalidValue unless before_s < after_s and pattern_s lies between them.
  void Check() const;
};

struct TripletMappingOptions {
  double akaze_threshold = 0.0003;  ///< AKAZE detector response threshold (OpenCV: 0.001)
  double ratio = 0.8;               ///< Lowe's ratio test on Hamming distances
  double ransac_px = 1.0;           ///< PnP RANSAC inlier threshold, px
  int min_inliers = 15;             ///< fewer: the AKAZE motion is not trusted
  double max_motion_mm = 20.0;      ///< a larger measured motion is rejected as implausible
  /// Wider images are searched for features at this width (keypoints scaled back): a full-size
  /// frame gives ~15 000 AKAZE features at full resolution, ~4× slower, for no better motion.
  int max_detect_width_px = 1300;

  /// Throws InvalidValue naming the field.
  void Check() const;
};

struct TripletMappingReport {
  std::string method = "none";  ///< "akaze", "odometry" or "none" (texture as it is)
  int features_before = 0, features_after = 0;
  int matches = 0;                   ///< after the ratio test and the cross check
  int inliers = 0;                   ///< PnP RANSAC inliers
  double reprojection_rms_px = 0.0;  ///< inliers, after refinement
  double motion_mm = 0.0;            ///< |translation| of after_from_before used
  double rotation_deg = 0.0;         ///< its rotation angle
  long long mapped_pixels = 0;       ///< pixels coloured from their 3-D point
  double time_ms = 0.0;
};

struct TripletMappingResult {
  cv::Mat3f color;  ///< colour at the pattern instant, aligned with the pattern's depth map
  Rigid3d after_from_before;    ///< camera motion used (identity for "none")
  Rigid3d pattern_from_before;  ///< the interpolated pose of the pattern camera
  TripletMappingReport report;
};

/// Rigid motion a fraction `s` of the way from `start` to `end`: rotation by slerp,
/// translation by linear interpolation (s = 0 gives start, s = 1 end).
Rigid3d InterpolatePose(const Rigid3d& start, const Rigid3d& end, double s);

/// Colours the pattern instant from the texture images `before` and `after` (same size and
/// units, any scale, linear or not). `depth_mm`: z at the pattern instant, aligned with the
/// camera (fill NaNs from the pipe prior first, texture/deblur.hpp); pixels whose depth stays
/// NaN keep the texture image nearer in time as it is. `velocity_mm_s`: the camera's velocity
/// from odometry (camera frame), used only when the images give no reliable motion.
TripletMappingResult MapTripletToPattern(
    const cv::Mat3f& before, const cv::Mat3f& after, const cv::Mat1f& depth_mm,
    const CameraModel& camera, const TripletTimes& times,
    const std::optional<Eigen::Vector3d>& velocity_mm_s = std::nullopt,
    const TripletMappingOptions& options = {});

}  // namespace sewer3d
