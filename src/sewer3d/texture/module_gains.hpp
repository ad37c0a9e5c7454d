#pragma once
/// \file
/// Colour consistency between the modules of a rig (issue 14: the same wall seen by two
/// neighbouring modules must look the same). Each module's shading correction maps the median
/// wall it saw to one common colour, which is right only when every module saw the same walls;
/// a short run, or modules staggered over a change of material, break that. Where neighbouring
/// modules see the same wall at (nearly) the same instant, the ratio of their corrected colours
/// measures their relative gain directly, whatever the wall: MeasureSeamRatio finds it for one
/// pair of images, SolveModuleGains the per-module gains that best explain all of them.

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/rigid3.hpp"

namespace sewer3d {

struct SeamOptions {
  int stride_px = 8;               ///< a's pixels sampled every stride-th row and column
  double max_depth_step_mm = 3.0;  ///< b's depth there must agree (else hidden or off its mesh)
  int min_points = 200;            ///< fewer common points: no measurement
  double min_linear = 0.01;        ///< darker colours (noise, shadow) are not compared
  void Check() const;
};

/// The corrected colour of a seen by both, over b's: per channel the median of log(a / b).
struct SeamRatio {
  cv::Vec3d log_ratio_bgr{0, 0, 0};
  int points = 0;
};

/// Compares two modules' corrected colour images (linear BGR, smoothed by the caller so that
/// the fine texture's registration does not matter) over the wall both see: a's pixels with
/// depth are moved into b's camera by `b_from_a`. Nullopt when fewer than min_points agree.
std::optional<SeamRatio> MeasureSeamRatio(const cv::Mat3f& colour_a, const cv::Mat1f& depth_a,
                                          const CameraModel& camera_a, const cv::Mat3f& colour_b,
                                          const cv::Mat1f& depth_b, const CameraModel& camera_b,
                                          const Rigid3d& b_from_a, const SeamOptions& options);

/// One measured seam between modules a and b.
struct SeamMeasurement {
  int a = 0, b = 0;
  SeamRatio ratio;
};

struct ModuleGains {
  std::vector<cv::Vec3d> gains_bgr;  ///< divide module m's corrected colour by gains_bgr[m]
  int seams = 0;                     ///< measurements used
  double rms_log_residual = 0.0;     ///< per channel and seam, after the fit
};

/// Per-module gains g minimising Σ points · (log g_a − log g_b − log_ratio_ab)² per channel,
/// with Σ log g = 0 over the modules that take part (the common colour stays); modules no seam
/// reaches keep gain 1. Throws std::invalid_argument for a module index out of range.
ModuleGains SolveModuleGains(int modules, const std::vector<SeamMeasurement>& seams);

}  // namespace sewer3d
