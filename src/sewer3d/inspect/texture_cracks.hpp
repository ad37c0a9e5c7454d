#pragma once
/// \file
/// Cracks seen in the texture (BAB): thin dark lines on the wall, longer than any mark of the
/// material itself, found on the coarse map's grey level (CoarseMap::grey). A crack one or two
/// millimetres open is narrower than the spacing of the depth maps' spots, so the displacement
/// map often shows it shallow or not at all; its shadow is in the texture (docs/inspection.md,
/// "Cracks in the texture").

#include <vector>

#include "sewer3d/inspect/coarse_map.hpp"
#include "sewer3d/inspect/observation.hpp"

namespace sewer3d {

struct TextureCrackOptions {
  bool enabled = true;
  double cell_mm = 0.4;             ///< grey map cell (CoarseMapBuilder's grey_cell_mm)
  double background_mm = 5.0;       ///< σ of the texture's local mean, taken off
  double contrast_mm = 10.0;        ///< σ of the window its local contrast is measured over
  double line_sigma_mm = 0.5;       ///< smoothing before a line's centre is compared with its sides
  double direction_sigma_mm = 1.0;  ///< smoothing for a line's direction (Hessian)
  double side_mm = 2.0;             ///< a line's sides are read this far from its centre
  /// The line response (sides minus centre) is averaged ± this along the line's direction: a
  /// crack keeps its response, the material's grains and pores (a few mm) lose theirs.
  double half_length_mm = 5.0;
  double seed_sigmas = 7.0;  ///< a crack reaches this many robust sigmas over the median
  double grow_sigmas = 3.5;  ///< and is the cells connected to that above this
  /// and is, there, darker than both its sides by this share of the wall's brightness
  /// (averaged along it): a crack's shadow is (concrete: 0.2–0.25), a featureless wall's
  /// faint streaks (plastic's extrusion lines, < 1 %) are not, however they stand out there.
  double min_darkness = 0.08;
  double min_length_mm = 30.0;
  double max_width_mm = 4.0;  ///< a piece of line this wide across (cells' spread) is a blob
  /// Pieces of one crack (one broken by a hole or a faint stretch): directions within this,
  /// each centre this close to the other's line, and at most this far apart along it.
  double merge_angle_deg = 10.0;
  double merge_offset_mm = 2.0;
  double merge_gap_mm = 20.0;
  /// Holes reaching this far from their edge are no crack (their edges are no line); a
  /// narrower hole is as dark as a crack's deepest part, where the depth maps lost its spots.
  double hole_mm = 2.0;
  double strip_mm = 200.0;  ///< the grey map is filtered in strips this long (memory)
  void Check() const;
};

/// BAB observations (ids and at_joint left to the caller) for the thin dark lines of
/// `map.grey` (empty: none) of a model of `radius_mm`, outside `excluded` (other
/// observations' crops, joints' bands: their edges are lines too), in fine map cells. Each with
/// length_mm, angle_deg (0 along the pipe, positive toward the later clock) and, where the
/// texture shows it, width_mm: the dark line's full width at half its depth.
std::vector<Observation> FindTextureCracks(const CoarseMap& map, double radius_mm,
                                           const std::vector<MapCrop>& excluded,
                                           const TextureCrackOptions& options);

}  // namespace sewer3d
