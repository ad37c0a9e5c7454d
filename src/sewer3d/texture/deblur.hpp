#pragma once
/// \file
/// Depth-graded motion deblur of a texture image (paper §3.2, issue 14 item 4). The robot moves
/// during the exposure, so each pixel is smeared along the image path of its 3-D point: a box
/// point-spread function whose length grows as the wall gets closer. Per pixel the blur length
/// comes from the depth and the camera's velocity; the image is restored line by line along the
/// dominant travel axis by a 1-D Wiener filter of a centred box of that length, with lengths
/// grouped in bins and blended linearly between neighbouring bins (no seams).
/// Pixels the decoder left without depth take it from a pipe prior first (depth_prior.hpp).

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "sewer3d/camera/camera_model.hpp"

namespace sewer3d {

struct DeblurOptions {
  double bin_px = 0.25;         ///< width of the blur-length bins
  double min_length_px = 0.5;   ///< shorter blurs are left as they are
  double max_length_px = 64.0;  ///< longer blurs are restored as this length (reported)
  /// Largest gain of the filter at any frequency: the output's noise is at most this many times
  /// the input's (RMS, white noise), and it limits the overshoot at sharp edges. It also sets
  /// the floor K0 ≥ (g − √(g² − 1))² of the Wiener noise-to-signal ratio (the DC-normalised
  /// filter (1 + K) H / (H² + K) peaks at (1 + K) / (2 √K) = g there).
  double max_gain = 4.0;
  /// Image noise sigma per channel in the image's units; ≤ 0: estimated from the image (median
  /// absolute difference of neighbouring pixels across the travel direction, per channel).
  double noise_sigma = 0.0;

  /// Throws InvalidValue naming the field.
  void Check() const;
};

struct DeblurReport {
  bool along_columns = true;   ///< lines restored: image columns (v) or rows (u)
  double off_axis_deg = 0.0;   ///< mean travel direction's angle from that axis (not restored)
  double min_length_px = 0.0;  ///< blur lengths over pixels with depth (along the axis)
  double max_length_px = 0.0;
  int bins = 0;                   ///< distinct length bins filtered
  long long pixels_restored = 0;  ///< pixels with a blur of at least min_length_px
  long long pixels_clamped = 0;   ///< pixels whose blur exceeded max_length_px
  double noise_sigma = 0.0;       ///< used (given or estimated), image units
  double noise_to_signal = 0.0;   ///< Wiener K0 used (K at the Nyquist frequency)
  double time_ms = 0.0;
};

struct DeblurResult {
  cv::Mat3f image;           ///< restored image, same size and units as the input
  cv::Mat1f blur_length_px;  ///< blur length along the restored axis; NaN without depth
  DeblurReport report;
};

/// Image displacement (px) of each pixel's 3-D point over the exposure: the point X = z · ray at
/// mid-exposure is projected from X + d/2 and X − d/2, d = velocity · exposure (the camera moves
/// by d, the point by −d in the camera frame). Returns (du, dv) per pixel, NaN where the depth is
/// NaN or a projection fails. velocity_mm_s: camera velocity in the camera frame.
cv::Mat2f BlurDisplacementPx(const CameraModel& camera, const cv::Mat1f& depth_mm,
                             const Eigen::Vector3d& velocity_mm_s, double exposure_ms);

/// Restores `image` (any units, linear or not) blurred by the camera's motion during
/// `exposure_ms`. `depth_mm` has the image's size; pixels with NaN depth keep their value (fill
/// it from PipePriorDepth first). With zero velocity the output equals the input.
DeblurResult Deblur(const cv::Mat3f& image, const cv::Mat1f& depth_mm, const CameraModel& camera,
                    const Eigen::Vector3d& velocity_mm_s, double exposure_ms,
                    const DeblurOptions& options = {});

}  // namespace sewer3d
