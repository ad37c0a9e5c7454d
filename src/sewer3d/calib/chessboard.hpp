#pragma once
/// \file
/// Checkerboard corner detection (OpenCV's detector, then sub-pixel refinement).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace sewer3d {

/// The cols x rows inner corners of a checkerboard in a grey image, in OpenCV's order (row
/// by row, the order BoardCorners uses), refined by cornerSubPix over a window scaled to the
/// smallest corner spacing (11 x 11 to 25 x 25 px); nullopt when
/// the board is not found whole.
std::optional<std::vector<Eigen::Vector2d>> DetectChessboard(const cv::Mat& grey, int cols,
                                                             int rows);

}  // namespace sewer3d
