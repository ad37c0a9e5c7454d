#pragma once
/// \file
/// The pipe's cross-section profile along its length, from the model's displacement map (the
/// fields of a laser profile survey, BFR Abwasser): per station height, width, inner
/// circumference, mean diameter, ovality, and the radius range. Formulas in docs/inspection.md
/// ("Profile").
///
/// A profile row is measured on a *ring*: the wall's distance r(θ) from the model's centreline
/// at clock angles θ (0 = crown, clockwise looking downstream, model/pipe_map.hpp), radius =
/// model radius + displacement. The ring is averaged into `ring_step_deg` sectors before
/// anything is measured, so per-cell noise neither lengthens the perimeter nor widens the
/// diameter range. Intrusions (a connection's stub, a deposit) shorten r(θ) locally: that is
/// real and shows in the minimum radius, height and width; nothing is rejected.

#include <span>
#include <vector>

#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

struct ProfileOptions {
  double step_mm = 10.0;  ///< one profile row at every multiple of step_mm of station
  /// Rows of the map averaged around each profile station (± half of this, mm; at least the
  /// row holding the station).
  double band_mm = 2.0;
  /// A row is measured only where at least this share of the circumference has data (coverage
  /// measured or filled) and no gap is wider than max_gap_deg; gaps up to max_gap_deg are
  /// bridged by linear interpolation around the ring.
  double min_coverage = 0.9;
  double max_gap_deg = 20.0;
  /// Sector width the ring is averaged into (an even number of sectors fits the turn, so a
  /// sector has one opposite; rounded to the nearest such width).
  double ring_step_deg = 1.0;
  /// Height and width: the diameters within ± this of 12–6 and 3–9 o'clock are averaged.
  double axis_half_width_deg = 2.0;
  double nominal_diameter_mm = 0.0;  ///< 0: twice the model radius
  void Check() const;
};

/// One cross-section. Lengths in mm, shares in %. NaN where the section is not measured well
/// enough (coverage below ProfileOptions::min_coverage or a gap wider than max_gap_deg).
struct ProfileRow {
  double station_mm = 0.0;
  double coverage = 0.0;          ///< share of the circumference with data (before bridging), 0..1
  double widest_gap_deg = 0.0;    ///< the widest run of clock angles without data
  double height_mm = 0.0;         ///< crown to invert (clock 12 to 6)
  double width_mm = 0.0;          ///< 9 to 3 o'clock
  double circumference_mm = 0.0;  ///< perimeter of the ring polygon
  double mean_diameter_mm = 0.0;  ///< circumference / π
  double min_diameter_mm = 0.0;   ///< over all directions (r(θ) + r(θ + π))
  double max_diameter_mm = 0.0;
  /// EN 13508-2 BAA: change of the vertical / horizontal dimension against the nominal
  /// diameter (negative: reduced).
  double vertical_change_pct = 0.0;
  double horizontal_change_pct = 0.0;
  double ovality_en_pct = 0.0;    ///< 100 (max − min diameter) / (max + min diameter)
  double ovality_astm_pct = 0.0;  ///< ASTM F1216: 100 (max − mean diameter) / mean diameter
  double min_radius_mm = 0.0;     ///< distance of the wall from the centreline
  double mean_radius_mm = 0.0;
  double max_radius_mm = 0.0;
};

struct Profile {
  double nominal_diameter_mm = 0.0;
  std::vector<ProfileRow> rows;
};

/// The profile of `maps` (a whole-run map or a tile; model radius `radius_mm`): one row at each
/// multiple of options.step_mm inside the grid's stations, in station order. Throws
/// std::invalid_argument on invalid options or a non-positive radius.
Profile ComputeProfile(const PipeMaps& maps, double radius_mm, const ProfileOptions& options);

/// The measures of one complete ring: `radius_mm[k]` is r at clock angle (k + ½) · 2π / n (all
/// finite, n ≥ 8), as in a map row. Sets every field but station_mm, coverage and
/// widest_gap_deg. Used by ComputeProfile and by evaluation against a true ring. Throws
/// std::invalid_argument when nominal_diameter_mm is not positive.
ProfileRow MeasureRing(std::span<const double> radius_mm, double nominal_diameter_mm,
                       const ProfileOptions& options);

}  // namespace sewer3d
