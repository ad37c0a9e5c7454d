#pragma once
/// \file
/// `sewer3d inspect`'s algorithm: EN 13508-2 observations from the pipe model's displacement
/// map (docs/inspection.md). On the coarse map: ring fits, joints (BAJ), sections between them,
/// the smooth wall per section and its deformation (BAA), then local defects on the residual
/// (BAG, BBC, BBE, BAF, BAB), and cracks in the texture outside all of these and the joints'
/// bands (BAB). Options in, observations + report out; no I/O.

#include <vector>

#include "sewer3d/inspect/coarse_map.hpp"
#include "sewer3d/inspect/defects.hpp"
#include "sewer3d/inspect/joints.hpp"
#include "sewer3d/inspect/observation.hpp"
#include "sewer3d/inspect/texture_cracks.hpp"
#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

struct InspectOptions {
  double cell_mm = 1.0;  ///< coarse map cell (coarse_map.hpp)
  /// Maps (and coarse cells) coarser than this are refused: a crack (≤ defects.
  /// crack_max_width_mm) must span 3 cells and a joint's gap its edges, or the findings are
  /// invented shapes (a 50 mm map gave an "80 mm wide crack" and joints with nothing measured).
  double max_map_cell_mm = 2.0;
  double nominal_diameter_mm = 0.0;  ///< DN; 0: twice the model radius
  double min_ring_coverage = 0.6;    ///< rows measured less around are not ring-fitted
  double smoothing_mm = 25.0;        ///< half window of the smooth wall along the pipe
  double min_deformation_pct = 1.0;  ///< BAA from this reduction of a diameter
  double joint_flag_mm = 10.0;       ///< observations this close to a joint get its flag
  /// The wall this close to a joint's gap is the joint's (its broken edges are not searched
  /// for local defects, and the smooth wall is fitted per section between the bands).
  double joint_band_mm = 10.0;
  JointOptions joints;
  DefectOptions defects;
  TextureCrackOptions cracks;  ///< cracks in the texture (needs the map's grey level)
  void Check() const;
};

struct InspectionReport {
  int coarse_rows = 0;
  int coarse_cols = 0;
  double cell_mm = 0.0;
  int valid_rings = 0;             ///< rows with a ring fit
  double residual_sigma_mm = 0.0;  ///< robust noise of the wall around its smooth shape
  int sections = 0;
  /// Stations (first and last coarse row centre) where the wall's smooth shape is known, so
  /// local defects were searched; NaN when nowhere.
  double inspected_from_mm = 0.0;
  double inspected_to_mm = 0.0;
  double inspected_share = 0.0;  ///< of the map's rows
};

struct Inspection {
  std::vector<Observation> observations;  ///< in station order, ids O1, O2, …
  InspectionReport report;
};

/// InvalidValue ("nominal_diameter_mm") when options' nominal diameter (0: the model's) lies
/// more than 25 % from the model's diameter (2 × radius_mm): its percentages would mean nothing.
void CheckNominalDiameter(const InspectOptions& options, double radius_mm);

/// Observations on `map` (CoarseMapBuilder) of a model with `centreline`. InvalidValue
/// ("map") when the map's cells are coarser than options.max_map_cell_mm. A joint with nothing
/// measured on either side, or neither a gap nor an offset, is no observation.
Inspection Inspect(const CoarseMap& map, const Centreline& centreline,
                   const InspectOptions& options);

}  // namespace sewer3d
