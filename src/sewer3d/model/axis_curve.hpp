#pragma once
/// \file
/// The smooth axis through the slices' circle centres (centreline_fit.hpp): local quadratic
/// regression over stations (or one straight line), resampling by arc length into a
/// Centreline, and the bend radius of a centreline.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

/// One slice centre at a station (the parameter of the current centreline estimate).
struct AxisSample {
  double station_mm = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};

/// The axis through `samples` at each of `at_stations`: with `straight`, the least-squares
/// line c(s) = a + b·s; otherwise a local quadratic in s fitted with tricube weights over
/// ±half_width_mm (widened where fewer than 4 samples fall in the window). A circular bend is
/// reproduced to ~w⁴/(8R³) (0.005 mm for w = 1 m, R = 30 m). Needs ≥ 2 samples (straight) or
/// ≥ 3 samples at distinct stations.
std::vector<Eigen::Vector3d> SmoothAxis(const std::vector<AxisSample>& samples,
                                        const std::vector<double>& at_stations,
                                        double half_width_mm, bool straight);

/// A Centreline from a densely sampled axis curve (consecutive points, any spacing ≪ its bend
/// radius): station = arc length, 0 where the curve passes the model frame's plane z = 0
/// (linearly extrapolated from the nearer end when it does not), samples every `step_mm` at
/// stations k·step covering the curve, crowns = −y of the model frame projected perpendicular
/// to the tangent. Returns nullopt if the curve has < 2 distinct points or never leaves z = 0
/// direction (tangent ⟂ z at the end that must be extrapolated, or tangent ∥ y).
std::optional<Centreline> ResampleAxis(const std::vector<Eigen::Vector3d>& curve, double step_mm);

/// The radius of the circle best fitting the centreline (projected on its best plane), or
/// nullopt when it deviates less than `min_sagitta_mm` from the chord between its ends.
std::optional<double> FitBendRadius(const Centreline& centreline, double min_sagitta_mm);

}  // namespace sewer3d
