#pragma once
/// \file
/// Local defects on the ring residual (coarse map minus the smooth wall, ring_fit.hpp): lateral
/// connections (a bore going deep outward; intruding BAG with the lateral's end standing
/// inward around it, else BCA), regions standing inward (deposits BBC, other obstacles BBE) or
/// outward (spalling BAF, cracks BAB), classified by shape and place and measured
/// (docs/inspection.md).

#include <vector>

#include "sewer3d/inspect/coarse_map.hpp"
#include "sewer3d/inspect/observation.hpp"

namespace sewer3d {

struct DefectOptions {
  double intrusion_mm = 3.0;  ///< a region standing this far inward is an observation
  double surface_mm = 1.5;    ///< a region this deep into the wall is an observation
  /// An outward region deeper than this (90th percentile) is the bore of a lateral
  /// connection; regions within connection_margin_mm of it belong to the connection.
  double bore_depth_mm = 15.0;
  double connection_margin_mm = 15.0;
  /// Thresholds are raised to this many times the residual's robust sigma where noisier.
  double noise_factor = 6.0;
  double min_area_mm2 = 50.0;     ///< smaller regions (and bores) are ignored
  double crack_elongation = 4.0;  ///< length / width from which an outward region is a crack
  double crack_max_width_mm = 6.0;
  double invert_half_h = 1.0;  ///< a deposit's middle lies within ± this of 6 o'clock
  /// Regions at the invert this near each other are one deposit (a bed's steep ramps lose
  /// spots: their measured islands stand apart from the bed).
  double deposit_join_mm = 30.0;
  /// A spall's mean depth is taken over its cells at least this far inside its outline: the
  /// rim's slope, widened by the depth maps' interpolation between spots, would make it read
  /// shallow by an amount that depends on the cameras' resolution.
  double spall_rim_mm = 2.0;
  /// Unmeasured cells that a surface region touches (a rough spalled floor loses spots) are
  /// part of it, and join the regions they touch, when the hole is at most this long and wide.
  double max_hole_mm = 200.0;
  void Check() const;
};

/// The cells of `cells` (row y, column x; any order, no duplicates) whose every cell within
/// the ellipse of half-axes `radius_rows`, `radius_cols` is also one of `cells`: the region
/// eroded by that ellipse. Empty when nothing is left.
std::vector<cv::Point> InteriorCells(const std::vector<cv::Point>& cells, int radius_rows,
                                     int radius_cols);

/// Observations (ids, at_joint left to the caller) from `residual` (rows × cols of `map`,
/// NaN where unknown or masked, e.g. joint bands). `radius_mm`: the model radius;
/// `nominal_diameter_mm` the DN quantities are relative to; `sigma_mm` the residual's noise.
std::vector<Observation> FindDefects(const CoarseMap& map, const cv::Mat1f& residual,
                                     double radius_mm, double nominal_diameter_mm, double sigma_mm,
                                     const DefectOptions& options);

}  // namespace sewer3d
