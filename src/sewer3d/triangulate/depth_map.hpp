#pragma once
/// \file
/// Dense depth aligned with the camera image from the sparse spot points: inverse depth 1/z
/// interpolated linearly (barycentric weights) inside the Delaunay triangles of the spot
/// centres — for a plane seen by a pinhole camera 1/z is an affine function of the pixel, so
/// the map is exact there, where linear z would bulge; triangles with an edge longer than
/// max_edge_px (holes, depth steps, the border of the lit area) stay empty (NaN).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace sewer3d {

/// `pixels[i]` is the camera position of a point with depth `depths_mm[i]` (> 0). Pixels
/// outside the image are ignored; pixel centres at integers.
cv::Mat1f InterpolateDepth(cv::Size image_size, const std::vector<Eigen::Vector2d>& pixels,
                           const std::vector<double>& depths_mm, double max_edge_px);

/// The pixels of a depth map that hold a depth (not NaN).
int CountDepthPixels(const cv::Mat1f& depth_mm);

}  // namespace sewer3d
