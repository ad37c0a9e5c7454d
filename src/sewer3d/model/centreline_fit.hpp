#pragma once
/// \file
/// The pipe's centreline (paper §4.4 fits one cylinder; real pipes bend and joints deflect):
/// robust circle fits of cross-section slices every `slice_spacing_mm` along the current axis
/// estimate (circle_fit.hpp), joined by a smooth axis (axis_curve.hpp), iterated from the
/// initial axis until the axis moves less than `convergence_mm`. One straight cylinder is the
/// special case `straight`. The model radius is the nominal one; the fitted radius is reported.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sewer3d/core/circle_fit.hpp"
#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

struct CentrelineFitOptions {
  double nominal_diameter_mm = 300.0;  ///< model radius = half of it (Centreline::radius_mm)
  /// The initial axis: through the model frame's origin along this direction (the carrier's
  /// z at the first image).
  Eigen::Vector3d initial_axis = Eigen::Vector3d::UnitZ();
  bool straight = false;           ///< one straight cylinder instead of a bending centreline
  double start_station_mm = 0.0;   ///< station of the model frame's plane z = 0
  double slice_spacing_mm = 30.0;  ///< slice thickness along the axis
  double step_mm = 10.0;           ///< spacing of the centreline's samples
  /// Half-width of the local quadratic window joining the slice centres: wider averages more
  /// slices; narrower follows tighter bends and joint deflections.
  double smoothing_half_width_mm = 600.0;
  int min_slice_points = 40;
  double min_slice_coverage_deg = 180.0;  ///< angular extent of a slice's inliers
  double min_inlier_fraction = 0.5;       ///< of a slice's points
  double slice_outlier_mm = 2.0;          ///< a slice centre this far off the axis is dropped,
  double slice_outlier_scales = 5.0;      ///< or this many robust scales, whichever is more
  int max_iterations = 6;
  double convergence_mm = 0.005;     ///< largest axis move of an iteration to stop
  double bend_min_sagitta_mm = 0.5;  ///< below this the centreline has no bend radius
  CircleFitOptions circle;

  void Check() const;
};

/// One slice as the last iteration fitted it.
struct SliceReport {
  double station_mm = 0.0;                           ///< centre of the slice
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< circle centre, model frame
  double radius_mm = 0.0;
  double ovality_mm = 0.0;  ///< amplitude of the 2θ term (CircleFit)
  double rms_mm = 0.0;
  double inlier_fraction = 0.0;
  double coverage_deg = 0.0;
  int points = 0;
  bool used = false;  ///< fitted well and on the axis
};

struct CentrelineFitReport {
  int slices_used = 0;
  int slices_rejected = 0;
  double radius_mm = 0.0;     ///< median of the used slices' radii (the fitted radius)
  double rms_mm = 0.0;        ///< RMS of the used slices' inlier residuals
  double axis_rms_mm = 0.0;   ///< RMS distance of the used slice centres to the axis
  double last_move_mm = 0.0;  ///< largest axis move of the last iteration
  int iterations = 0;
  std::optional<double> bend_radius_mm;  ///< a single circular bend's radius, if any
  std::vector<SliceReport> slices;
};

struct CentrelineFit {
  bool converged = false;  ///< false: too few usable slices (centreline then empty)
  Centreline centreline;
  CentrelineFitReport report;
};

/// Fits the centreline to `points_model` (a subsample of the registered clouds, model frame).
/// Stations are arc length along the fitted axis, start_station_mm where it passes z = 0.
CentrelineFit FitCentreline(const std::vector<Eigen::Vector3d>& points_model,
                            const CentrelineFitOptions& options);

}  // namespace sewer3d
