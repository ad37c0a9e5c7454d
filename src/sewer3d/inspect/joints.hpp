#pragma once
/// \file
/// Joints on the coarse map (EN 13508-2 BAJ): found as an open gap (a narrow ring-wide groove)
/// or a step of the wall's axis offset, then measured from both sides (docs/inspection.md):
/// A the gap (groove area over its depth), B the radial offset of the next pipe at the joint
/// and where it is largest, C the angular deflection between the two pipes' axes.

#include <vector>

#include "sewer3d/inspect/coarse_map.hpp"
#include "sewer3d/inspect/ring_fit.hpp"
#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

struct JointOptions {
  double min_gap_depth_mm = 0.5;  ///< deeper cells count as open (gap bottom)
  double max_gap_mm = 40.0;       ///< wider grooves are not joint gaps
  double min_offset_mm = 0.7;     ///< without a gap, an axis-offset step at least this large
  double side_length_mm = 40.0;   ///< wall used on each side of the joint
  double side_margin_mm = 2.0;    ///< left out between the gap and each side
  /// The width left out around a joint at least (its measured gap where wider): a gap not in
  /// the data (found by its step) or only partly, and the blur of its edges, where depth-map
  /// triangles still join the two pipes' walls (up to 5.5 spot steps, ~15 mm of wall at
  /// 648 px): a side line that starts in the blur takes part of the step as slope, a
  /// deflection toward the offset's clock.
  double unseen_gap_mm = 18.0;
  /// Columns whose wall on either side departs from a straight line by more than this many
  /// times the median side's RMS are left out of the offset and deflection (a connection,
  /// deposit or spall in the side's rows).
  double max_side_rms_factor = 5.0;
  /// A row is open where it is missing, or deeper than min_gap_depth_mm below its column's
  /// median; a gap is a run of rows open over at least this share of the turn.
  double min_gap_share = 0.5;
  /// The gap's width comes from the columns where it is open (missing or deep) when at least
  /// this share of the columns is: where the depth maps bridge a gap no lost spot fell into
  /// (its columns read 0), they say nothing of its width. Where fewer are open, from all
  /// columns.
  double min_open_share = 1.0 / 3.0;
  /// How far a column's gap may reach beyond the half of the open rows' width found around
  /// the turn: a deflected joint's gap opens by R tan α on one side (2.6 mm for 1° in DN300),
  /// and near an offset the model's centreline tilts the gap across the map by a millimetre
  /// or two.
  double gap_reach_mm = 4.0;
  void Check() const;
};

struct JointMeasure {
  double station_mm = 0.0;  ///< centre of the gap (or of the step)
  double gap_mm = 0.0;
  double gap_depth_mm = 0.0;      ///< depth of the gap's bottom where seen, else 0
  double offset_mm = 0.0;         ///< radial offset of the next pipe's wall at the joint
  double offset_clock_rad = 0.0;  ///< where the next pipe's wall stands furthest inward
  double deflection_deg = 0.0;
  double deflection_clock_rad = 0.0;  ///< direction toward which the next pipe's axis turns
  double side_coverage = 0.0;         ///< share of the clock columns measured on both sides
  int row_begin = 0;                  ///< coarse rows of the joint band (gap + margins)
  int row_end = 0;
};

/// The joints of `map` in station order. `fits` are its ring fits (FitRings), `centreline` the
/// model's (its turning between the two sides adds to the deflection the wall shows).
std::vector<JointMeasure> FindJoints(const CoarseMap& map, const std::vector<RingFit>& fits,
                                     const Centreline& centreline, const JointOptions& options);

/// Measures a joint centred at `station_mm` with an open gap about `gap_guess_mm` wide (0:
/// none): per clock column a straight line through the wall on each side; the gap per column
/// is the open length between them (missing cells, and cells below the lines as a share of the
/// gap's depth), its median the gap; then with the sides beyond that gap, both lines
/// extrapolated to the joint: the first harmonic of their difference is the offset, that of
/// their slopes' difference plus the centreline's turn the deflection.
JointMeasure MeasureJoint(const CoarseMap& map, const Centreline& centreline, double station_mm,
                          double gap_guess_mm, const JointOptions& options);

}  // namespace sewer3d
