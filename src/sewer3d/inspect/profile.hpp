#pragma once
/// \file
/// The pipe's cross-section profile along its length, from the model's displacement map (the
/// fields of a laser profile survey, BFR Abwasser): per station height, width, inner
/// circumference, mean diameter, ovality, and the radius range. Formulas in docs/inspection.md.

#include <vector>

#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

struct ProfileOptions {
  double step_mm = 10.0;  ///< one profile row every step_mm of station
  /// Rows of the map averaged around each profile station (± half of this, mm).
  double band_mm = 2.0;
  /// A row is reported only where at least this share of the circumference is measured
  /// (coverage measured or filled); gaps up to max_gap_deg are bridged by interpolation.
  double min_coverage = 0.9;
  double max_gap_deg = 20.0;
  double nominal_diameter_mm = 0.0;  ///< 0: twice the model radius
  void Check() const;
};

/// One cross-section. Lengths in mm, shares in %. NaN where the section is not measured well
/// enough (coverage below ProfileOptions::min_coverage).
struct ProfileRow {
  double station_mm = 0.0;
  double coverage = 0.0;   ///< measured share of the circumference, 0..1
  double height_mm = 0.0;  ///< crown to invert (clock 12 to 6)
  double width_mm = 0.0;   ///< 9 to 3 o'clock
  double circumference_mm = 0.0;
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

/// The profile of `maps` (a whole-run map or a tile; model radius `radius_mm`).
Profile ComputeProfile(const PipeMaps& maps, double radius_mm, const ProfileOptions& options);

}  // namespace sewer3d
