#pragma once
/// \file
/// 3-D geometry of an RGB-D acquisition's depth map (docs/rgbd.md: z in mm in the camera frame
/// at the pattern instant, NaN = none): points and normals per pixel, sub-pixel lookups.

#include <Eigen/Core>
#include <limits>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "sewer3d/camera/camera_model.hpp"

namespace sewer3d {

/// One acquisition as the RGB-D stage writes it (docs/rgbd.md): colour and depth aligned,
/// both the camera's size; depth z in mm in the camera frame, NaN where none.
struct RgbdImage {
  cv::Mat3b color_bgr;
  cv::Mat1f depth;
};

/// The point of every pixel: P = z · (x, y, 1) with (x, y) the pixel's undistorted normalised
/// coordinates (camera frame, mm); NaN where the depth is not finite or positive, or the pixel
/// lies beyond the lens fold. Throws std::invalid_argument when the sizes differ.
cv::Mat3f PointMap(const cv::Mat1f& depth, const CameraModel& camera);

/// Unit normals of the surface a point map samples: the points are averaged over a
/// smooth_px × smooth_px box (1: none; depth noise would otherwise tilt the normals by
/// ~σ_z / pixel pitch), then the cross product of central differences ±step_px along rows and
/// columns, oriented toward the camera. NaN where a pixel of the box or one of the four
/// neighbours is missing, or a neighbour lies farther than max_step_mm from the centre point
/// (a depth discontinuity).
cv::Mat3f NormalMap(const cv::Mat3f& points, int step_px, int smooth_px, double max_step_mm);

/// The variance (rad², per tangent direction) of the noise in a normal map: each normal is
/// compared with the mean of its four neighbours `offset_px` away along rows and columns (so a
/// smooth surface's curvature cancels to first order) and the median squared difference is
/// turned into the variance of one tangential component, assuming Gaussian noise independent
/// between normals `offset_px` apart. 0 when fewer than 10 normals can be compared.
double NormalNoiseVariance(const cv::Mat3f& normals, int offset_px);

/// Bilinear interpolation of a one-channel map at a pixel position (pixel centres at integer
/// coordinates); nullopt outside the image, where one of the four pixels is NaN, or where they
/// spread over more than max_spread (a step between them).
std::optional<double> SampleBilinear(const cv::Mat1f& map, const Eigen::Vector2d& pixel,
                                     double max_spread = std::numeric_limits<double>::infinity());
/// The same for a three-channel map; the spread is the largest distance of a corner from
/// their mean.
std::optional<Eigen::Vector3d> SampleBilinear(
    const cv::Mat3f& map, const Eigen::Vector2d& pixel,
    double max_spread = std::numeric_limits<double>::infinity());

/// The points (camera frame, mm) of every `step_px`-th pixel of a depth map (rows and columns,
/// starting at step_px / 2) that has a depth; as PointMap, without unprojecting the others.
std::vector<Eigen::Vector3d> SampleDepthPoints(const cv::Mat1f& depth, const CameraModel& camera,
                                               int step_px);

}  // namespace sewer3d
