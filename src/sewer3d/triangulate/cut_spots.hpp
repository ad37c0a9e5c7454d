#pragma once
/// \file
/// Spots a depth step cut: where the edge of a joint's near wall crosses an element's disk,
/// the camera sees part of the disk only (the part on the gap's floor beyond the edge, or the
/// part the edge leaves in view), and that part's centroid lies off the element's centre
/// along the epipolar line: triangulated with the element's ray it lands off the wall,
/// millimetres off when the part is a sliver (docs/decoder.md, "Hard surfaces"). Such a spot
/// is smaller than its neighbours, and only at a step is a small spot a cut one: elsewhere a
/// small spot is a faint or far one and its centroid is sound.

#include <span>
#include <vector>

#include "sewer3d/core/neighbours.hpp"
#include "sewer3d/decode/decoder.hpp"
#include "sewer3d/triangulate/correspondences.hpp"
#include "sewer3d/triangulate/element_mesh.hpp"

namespace sewer3d {

struct CutSpotOptions {
  bool enabled = true;  ///< false: keep every point
  /// A step near a point: no affine map from element coordinates to camera pixels fits the
  /// points of its mesh neighbours and theirs (the point left out) to within this fraction of
  /// the frame's epipolar tolerance, at least max_fit_px (the lost-spot search's fit limit:
  /// smooth walls fit, a step's disparity jump does not).
  double max_fit_tolerance = 0.7;
  double max_fit_px = 1.0;
  /// Points needed among those neighbours to judge the fit (three define it).
  int min_neighbours = 5;
  /// A cut spot: its area under this fraction of the median of its mesh neighbours' spots'.
  double area_fraction = 0.6;
  void Check() const;
};

/// Removes the points (the others keep their order) whose spot a depth step cut: a spot
/// smaller than `area_fraction` of its mesh neighbours' (`neighbours`: MeshNeighbours of
/// `mesh`) with a step among them. `area_px[i]`: the area of observation i's spot;
/// `tolerance_px`: the frame's epipolar tolerance (TriangulationStats::tolerance_px).
/// Returns the number removed.
int RejectCutSpots(std::vector<TriangulatedPoint>& points,
                   const std::vector<CodedObservation>& observations, std::span<const int> area_px,
                   const ElementMesh& mesh, const NeighbourLists& neighbours, double tolerance_px,
                   const CutSpotOptions& options);

}  // namespace sewer3d
