#pragma once
/// \file
/// The pipe's centreline in the registration's fusion (posegraph/axis_curve.hpp): every node
/// whose instant's walls gave the pipe's axis (AcquisitionNode::axis_in_camera) is tied to one
/// curve estimated with the poses, and the curve's bending costs. The carrier wanders and tilts
/// inside the pipe, so a prior on its own path would fight real motion; the axis it sees does
/// not move. Where the pairwise edges hardly see the turn across the pipe (plastic: projection
/// edges), this holds the trajectory to a straight pipe; where they see a bend (texture), they
/// keep it, and the curve follows.

#include <optional>
#include <vector>

#include "sewer3d/posegraph/axis_curve.hpp"
#include "sewer3d/register/initial_poses.hpp"

namespace sewer3d {

struct CentrelineOptions {
  bool enabled = true;
  double spacing_mm = 100.0;  ///< between control points
  /// The curve's bend costs χ² = (R / r)² per metre of pipe bent to radius r, with R:
  /// - `bend_radius_mm` where feature edges see the pipe's turn (texture): they measure a bend,
  ///   and the prior only keeps the curve smooth (the gentlest bend a pipe may have);
  /// - `featureless_bend_radius_mm` where none do (projection edges only: plastic): there every
  ///   registration carries the same small turn of the modules' calibration errors, which
  ///   nothing in a featureless pipe tells from a bend; a sewer is laid straight between
  ///   manholes, so the curve is held straight (an apparent bend of 460 m costs 118 per metre).
  double bend_radius_mm = 30000.0;
  double featureless_bend_radius_mm = 5.0e6;
  /// One instant's axis point across the pipe (σ per direction); the instant's nodes share it
  /// (each σ · √nodes).
  double axis_sigma_mm = 0.05;
  double axis_along_sigma_mm = 5.0;  ///< along the pipe: anchors the curve's stations only
  double spacing_sigma_mm = 1.0;     ///< of a second difference along the curve

  void Check() const;
};

/// A stretch of stations (mm) that feature edges span.
struct StationSpan {
  double from_mm = 0.0, to_mm = 0.0;
};

/// The curve and the observations of the graph.
struct CentrelineSetup {
  AxisCurve curve;
  std::vector<AxisObservation> observations;
  int featureless_points = 0;  ///< second differences with featureless_bend_radius_mm
};

/// The curve over the stations of the nodes with an axis point (their odometry distance), on
/// the straight line that best fits their axis points at the initial poses; a second
/// difference is textured (bend_radius_mm) where a span lies within one spacing of its centre,
/// featureless elsewhere. nullopt when the option is off or fewer than two counters have an
/// axis point.
std::optional<CentrelineSetup> MakeCentreline(const std::vector<AcquisitionNode>& nodes,
                                              const std::vector<StationSpan>& textured,
                                              const CentrelineOptions& options);

/// Moves each observation's station to where its node's axis point lies along the curve at
/// these poses (kept within a control point beyond the curve's ends).
void ReassociateStations(CentrelineSetup& setup, const std::vector<Rigid3d>& poses);

struct CentrelineReport {
  int observations = 0;
  int points = 0;          ///< control points
  double length_mm = 0.0;  ///< from the first to the last control point
  /// The nodes' axis points from the curve, across it (mm).
  double across_rms_mm = 0.0, across_max_mm = 0.0;
  /// The curve's bend: the radius of the circle through its first, middle and last control
  /// points (mm; infinity when they are collinear or the curve is shorter than 1 m), and the
  /// largest distance of a control point from the chord of the first and the last.
  double bend_radius_mm = 0.0;
  double max_sagitta_mm = 0.0;
  int featureless_points = 0;  ///< second differences held with featureless_bend_radius_mm
};

CentrelineReport ReportCentreline(const CentrelineSetup& setup, const std::vector<Rigid3d>& poses);

}  // namespace sewer3d
