#pragma once
/// \file
/// Connected regions of a map on the cylinder (columns wrap around the clock).

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>
#include <vector>

namespace sewer3d {

/// A connected region: its cells as (x = column, y = row) with columns unwrapped, so that a
/// region across the seam at 12 o'clock has contiguous x (x may be negative or ≥ cols).
struct MapComponent {
  std::vector<cv::Point> cells;
  int row_min = 0;
  int row_max = 0;
  int col_min = 0;  ///< unwrapped
  int col_max = 0;
};

/// Hysteresis regions of `values`: 8-connected cells with sign · value ≥ low that contain at
/// least one cell with sign · value ≥ high (sign +1 or −1; NaN cells belong to none).
std::vector<MapComponent> HysteresisComponents(const cv::Mat1f& values, double sign, double low,
                                               double high);

/// Hysteresis regions of a map of levels (0: none, 1: may join, 2: seed): 8-connected cells of
/// level ≥ 1 that contain at least one seed.
std::vector<MapComponent> HysteresisComponents(const cv::Mat1b& levels);

}  // namespace sewer3d
