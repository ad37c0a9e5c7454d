#pragma once
/// \file
/// Dense depth aligned with the camera image from the sparse spot points: z interpolated
/// linearly inside the Delaunay triangles of the spot centres; triangles with an edge longer
/// than max_edge_px (holes, depth steps, the border of the lit area) stay empty (NaN).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace sewer3d {

/// `pixels[i]` is the camera position of a point with depth `depths_mm[i]`.
cv::Mat1f InterpolateDepth(cv::Size image_size, const std::vector<Eigen::Vector2d>& pixels,
                           const std::vector<double>& depths_mm, double max_edge_px);

}  // namespace sewer3d
