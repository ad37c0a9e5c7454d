#include "sewer3d/model/pipe_map.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

Eigen::Vector3d AxisFrame::Direction(double clock_rad) const {
  return std::cos(clock_rad) * crown + std::sin(clock_rad) * right;
}

double Centreline::EndStationMm() const {
  if (points.empty()) return station0_mm;
  return station0_mm + static_cast<double>(points.size() - 1) * step_mm;
}

Eigen::Vector3d Centreline::TangentAt(std::size_t i) const {
  SEWER3D_CHECK(points.size() >= 2 && i < points.size());
  const std::size_t lo = i == 0 ? 0 : i - 1;
  const std::size_t hi = std::min(i + 1, points.size() - 1);
  return (points[hi] - points[lo]).normalized();
}

AxisFrame Centreline::FrameAt(double station_mm) const {
  SEWER3D_CHECK(points.size() >= 2 && crowns.size() == points.size() && step_mm > 0.0);
  const double last = static_cast<double>(points.size() - 1);
  const double u = (station_mm - station0_mm) / step_mm;
  AxisFrame f;
  Eigen::Vector3d crown;
  if (u <= 0.0 || u >= last) {
    // Beyond the ends the axis goes on straight along the end tangent.
    const std::size_t end = u <= 0.0 ? 0 : points.size() - 1;
    f.tangent = TangentAt(end);
    f.origin = points[end] + (u - static_cast<double>(end)) * step_mm * f.tangent;
    crown = crowns[end];
  } else {
    const auto i = std::min(static_cast<std::size_t>(u), points.size() - 2);
    const double w = u - static_cast<double>(i);
    f.origin = (1.0 - w) * points[i] + w * points[i + 1];
    f.tangent = ((1.0 - w) * TangentAt(i) + w * TangentAt(i + 1)).normalized();
    crown = (1.0 - w) * crowns[i] + w * crowns[i + 1];
  }
  f.crown = (crown - crown.dot(f.tangent) * f.tangent).normalized();
  f.right = f.tangent.cross(f.crown);
  return f;
}

double MapGrid::ColClockRad(int col) const {
  SEWER3D_CHECK(cols > 0);
  return (col + 0.5) * 2.0 * std::numbers::pi / cols;
}

MapGrid MapGrid::Tile(int first_row, int tile_rows) const {
  SEWER3D_CHECK(first_row >= 0 && tile_rows >= 0 && first_row + tile_rows <= rows);
  MapGrid tile = *this;
  tile.station0_mm = station0_mm + first_row * resolution_mm;
  tile.rows = tile_rows;
  return tile;
}

MapGrid MakeMapGrid(double begin_mm, double end_mm, double radius_mm, double resolution_mm) {
  ValidatePositive("resolution_mm", resolution_mm);
  ValidatePositive("radius_mm", radius_mm);
  SEWER3D_VALIDATE(
      end_mm > begin_mm, "stations",
      "the end (" << end_mm << " mm) must lie beyond the begin (" << begin_mm << " mm)");
  MapGrid grid;
  grid.resolution_mm = resolution_mm;
  grid.station0_mm = begin_mm;
  grid.rows = static_cast<int>(std::ceil((end_mm - begin_mm) / resolution_mm - 1e-9));
  grid.cols = static_cast<int>(std::lround(2.0 * std::numbers::pi * radius_mm / resolution_mm));
  return grid;
}

}  // namespace sewer3d
