#pragma once
/// \file
/// Connected regions of a map on the cylinder (columns wrap around the clock).

#include <Eigen/Core>
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

/// The principal axis of `cells` (x = column, unwrapped; y = row; not empty) on a wall of
/// cells `row_mm` × `col_mm`, in mm as (along the pipe, around it): the centre, the unit
/// direction (its along part ≥ 0), how far the cells reach along it from the centre (lo ≤ 0 ≤
/// hi) and their variance across it.
struct CellAxis {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  Eigen::Vector2d dir = Eigen::Vector2d::UnitX();
  double lo = 0.0;
  double hi = 0.0;
  double across_variance_mm2 = 0.0;
  /// The direction on the unrolled wall in degrees, 0 along the pipe, in (−90, 90].
  [[nodiscard]] double AngleDeg() const;
};
CellAxis PrincipalAxis(const std::vector<cv::Point>& cells, double row_mm, double col_mm);

/// The root of `i` in a union-find forest (`parent[i] == i` at a root), halving the path.
int FindRoot(std::vector<int>& parent, int i);

/// `regions` (cells of `values`' grid) joined where unmeasured cells split them: the holes of
/// `values` (8-connected NaN cells, not touching its first or last row, at most `max_rows` ×
/// `max_cols` across) that touch a region belong to it, and regions touching one hole become
/// one. A joined region lists its regions' cells first (in their order), then its holes'
/// (columns unwrapped next to the first region's). Regions touching no hole come back as they
/// were; the order is that of each result's first region.
std::vector<MapComponent> JoinThroughHoles(const std::vector<MapComponent>& regions,
                                           const cv::Mat1f& values, int max_rows, int max_cols);

}  // namespace sewer3d
