#pragma once
/// \file
/// Unrolling (paper §4.4): a point of the model frame to (station, clock, radius) in the
/// centreline's moving frame, and back. The station of a point is the one whose normal plane
/// holds it: (p − origin(s)) · tangent(s) = 0; the frame turns continuously along the
/// centreline (pipe_map.hpp), so for a point closer to the axis than the bend radius that
/// station is unique.

#include <Eigen/Core>

#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

/// A point in the pipe's cylindrical coordinates.
struct CylPoint {
  double station_mm = 0.0;
  double clock_rad = 0.0;  ///< [0, 2π): 0 at the crown, π/2 at 3 o'clock
  double radius_mm = 0.0;  ///< distance from the axis in the normal plane
};

/// `clock_rad` wrapped into [0, 2π).
double WrapClock(double clock_rad);

/// The cylindrical coordinates of `p_model` (model frame). Starts from `station_guess_mm` (a
/// neighbour's station makes it faster; any guess on the centreline converges) and iterates
/// s ← s + (p − origin(s))·tangent(s), which contracts by radius/bend radius per step, to
/// |residual| < 1e-9 mm. Stations beyond the ends follow the straight extension (FrameAt).
CylPoint Unroll(const Centreline& centreline, const Eigen::Vector3d& p_model,
                double station_guess_mm = 0.0);

/// The point at (station, clock, radius): origin(s) + radius · direction(clock) — a map point
/// when radius = model radius + displacement.
Eigen::Vector3d PointAt(const Centreline& centreline, const CylPoint& cyl);

}  // namespace sewer3d
