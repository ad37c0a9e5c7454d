#pragma once
/// \file
/// The pipe's centreline estimated with the poses (issue 15: the "apparently bent pipe" of a
/// featureless pipe). Where the registrations hardly see the turn across the pipe, their small
/// errors random-walk into a bent trajectory. The carrier wanders inside the pipe, so its path
/// may not be held straight; the pipe's axis may: what the depth maps of one instant say —
/// where the axis lies in the carrier's frame — ties every node to a common curve, and that
/// curve's bending costs.
///
/// - The curve: control points c_k at stations s₀ + k·h (mm along the pipe, the odometry's
///   distance), joined by straight segments.
/// - An axis observation of a node: a point x of the axis in the node's frame at station s.
///   Residual: d = (R x + t) − c(s) split along the segment's direction T into the part across
///   the curve, (I − T Tᵀ) d / σ (three components, rank two), and the part along it,
///   Tᵀ d / σ_along (only anchors the curve's stations; the caller moves s to where the node
///   lies along the curve between solves, `ProjectStation`).
/// - Curvature: the second difference D = c_{k+2} − 2 c_{k+1} + c_k is h² κ across the chord
///   c_{k+2} − c_k for a curve of curvature κ. Residual: D⊥ / σ₂, and along the chord
///   Tᵀ D / σ_along (keeps the control points evenly spread where no node is). σ₂ per second
///   difference: how much bend the caller lets the pipe have there.

#include <Eigen/Core>
#include <vector>

#include "sewer3d/core/rigid3.hpp"

namespace sewer3d {

struct AxisCurve {
  double start_station_mm = 0.0;
  double spacing_mm = 100.0;
  std::vector<Eigen::Vector3d> points;  ///< world frame, at start + k · spacing
  /// σ₂ of each second difference across its chord (points.size() − 2 of them: the one centred
  /// on point k + 1 at index k).
  std::vector<double> curvature_sigma_mm;
  double along_sigma_mm = 1.0;  ///< and along it

  /// Index of the segment that holds `station` (the first or the last beyond the ends).
  int Segment(double station_mm) const;
  /// Where `station` lies on `segment`: 0 at its first point, 1 at its second.
  double Fraction(int segment, double station_mm) const {
    return (station_mm - start_station_mm) / spacing_mm - segment;
  }
  /// c(s): linear on the segment (extrapolated beyond the ends).
  Eigen::Vector3d At(double station_mm) const;
};

struct AxisObservation {
  int node = 0;
  Eigen::Vector3d in_node = Eigen::Vector3d::Zero();  ///< a point of the pipe's axis, mm
  double station_mm = 0.0;
  double sigma_mm = 0.05;       ///< across the axis, per direction
  double along_sigma_mm = 5.0;  ///< along it
};

/// [(I − T Tᵀ) d / σ ; Tᵀ d / σ_along] with d = world_from_node · x − c(s), T the direction of
/// the segment that holds s.
Eigen::Vector4d AxisResidual(const AxisObservation& observation, const Rigid3d& world_from_node,
                             const AxisCurve& centreline);

/// [D⊥ / σ₂ ; Tᵀ D / σ_along] of the second difference centred on control point k + 1.
Eigen::Vector4d CurvatureResidual(const AxisCurve& centreline, int k);

/// The station where the node's axis point lies along the curve: s + Tᵀ d.
double ProjectStation(const AxisObservation& observation, const Rigid3d& world_from_node,
                      const AxisCurve& centreline);

}  // namespace sewer3d
