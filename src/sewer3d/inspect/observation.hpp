#pragma once
/// \file
/// Coded observations of an inspection (EN 13508-2 main codes), as `sewer3d inspect` finds them
/// on the pipe model's maps (docs/inspection.md). Stations in mm along the model's centreline
/// (the model's own stations: start station included), clock positions in hours, 12 = crown,
/// 3 = right looking downstream, as in the maps (model/pipe_map.hpp).

#include <string>
#include <vector>

namespace sewer3d {

/// One quantity of an observation: `name` as in the exchange files ("offset_mm", "gap_mm",
/// "deflection_deg", "intrusion_pct_of_dn", …), its value and unit ("mm", "deg", "%", "mm2").
/// A value of NaN is one the maps do not show (a joint's gap narrower than the depth maps
/// resolve): not measured, never 0 — null in observations.json, empty in the CSV, left out of
/// the ISYBAU file.
struct Quantity {
  std::string name;
  double value = 0.0;
  std::string unit;

  [[nodiscard]] bool Measured() const;
};

/// Where in the maps an observation was seen: rows [row0, row0 + rows) and columns
/// [col0, col0 + cols) of the whole-run map grid (columns may run past cols and wrap).
struct MapCrop {
  int row0 = 0;
  int rows = 0;
  int col0 = 0;
  int cols = 0;
};

struct Observation {
  std::string id;    ///< O1, O2, … in station order
  std::string code;  ///< EN 13508-2 main code: BAJ, BAA, BAG, BAF, BAB, BBC
  /// EN 13508-2 characterisation letter where the code has one (BAJ: "B" radial offset is
  /// the governing one when present, "A" gap, "C" deflection; BAA: "A" vertical, "B"
  /// horizontal); empty otherwise.
  std::string characterisation;
  /// Where it starts for continuous observations (deformation BAA, deposits BBC: they run
  /// over a stretch) or its centre for local ones (IsContinuous).
  double station_mm = 0.0;
  double length_mm = 0.0;  ///< extent along the pipe; 0 for a point observation
  double clock_h = 12.0;   ///< where it is most pronounced
  double clock_from_h = 12.0;
  double clock_to_h = 12.0;  ///< clockwise from clock_from_h; equal for a point
  bool at_joint = false;     ///< EN 13508-2 joint flag
  double confidence = 0.0;   ///< 0..1: how clearly the maps show it (docs/inspection.md)
  /// Quantification 1 and 2 of the exchange formats are quantities[0] and [1].
  std::vector<Quantity> quantities;
  MapCrop crop;        ///< the map region it came from
  std::string remark;  ///< a short plain-language description ("joint offset 6.1 mm at 1 h")

  /// The quantity called `name`; nullptr when the observation has none.
  [[nodiscard]] const Quantity* Find(const std::string& name) const;
};

/// True for observations that run over a stretch of pipe (BAA, BBC): station_mm is their start.
bool IsContinuous(const Observation& o);

}  // namespace sewer3d
