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

AxisFrame Centreline::FrameAt(double station_mm) const {
  SEWER3D_CHECK(points.size() >= 2 && crowns.size() == points.size() && step_mm > 0.0);
  const double u = std::clamp((station_mm - station0_mm) / step_mm, 0.0,
                              static_cast<double>(points.size() - 1));
  const auto i = std::min(static_cast<std::size_t>(u), points.size() - 2);
  const double w = u - static_cast<double>(i);
  AxisFrame f;
  f.tangent = (points[i + 1] - points[i]).normalized();
  // Extrapolate linearly beyond the ends so the frame follows the axis's last direction.
  const double s = (station_mm - station0_mm) / step_mm - static_cast<double>(i);
  f.origin = points[i] + s * (points[i + 1] - points[i]);
  const Eigen::Vector3d crown = (1.0 - w) * crowns[i] + w * crowns[i + 1];
  f.crown = (crown - crown.dot(f.tangent) * f.tangent).normalized();
  f.right = f.tangent.cross(f.crown);
  return f;
}

double MapGrid::ColClockRad(int col) const {
  SEWER3D_CHECK(cols > 0);
  return (col + 0.5) * 2.0 * std::numbers::pi / cols;
}

}  // namespace sewer3d
