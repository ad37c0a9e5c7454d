#pragma once
/// \file
/// The lit elements of a module's projected pattern, meshed once per module: a Delaunay
/// triangulation of their centres in projector element coordinates. Its triangles join
/// neighbouring lit elements and hold no other lit element, so a depth map filled only over
/// the triangles whose three elements became points never bridges a lit element that did not:
/// a spot lost in a joint's gap, in the shadow band of a depth step, in a dark patch.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/core/neighbours.hpp"
#include "sewer3d/pattern/binary_array.hpp"

namespace sewer3d {

struct ElementMesh {
  /// Element grid covered: rows row0 .. row0 + rows − 1, columns col0 .. col0 + cols − 1
  /// (absolute element indices of the pattern's tiling, PatternLayout::ElementCentre).
  int row0 = 0, col0 = 0, rows = 0, cols = 0;
  /// Grid indices (Index) of each triangle's lit elements, counter-clockwise in (column, row).
  std::vector<std::array<int, 3>> triangles;
  /// (r − row0) · cols + (c − col0); −1 outside the grid.
  int Index(int r, int c) const {
    if (r < row0 || c < col0 || r >= row0 + rows || c >= col0 + cols) return -1;
    return (r - row0) * cols + (c - col0);
  }
};

/// The lit elements (BinaryArray::tiled) whose centres fall on the projector image, meshed.
/// Throws InvalidValue ("pattern.pitch_px") where pitch and offset lay more than 2^26
/// elements over the projector or start the grid beyond ±1e9 elements.
ElementMesh MeshLitElements(const ModuleDescription& module, const BinaryArray& pattern);

/// Each lit element's neighbours in the mesh (the elements it shares a triangle with), by grid
/// index (ElementMesh::Index); elements of no triangle have none.
NeighbourLists MeshNeighbours(const ElementMesh& mesh);

}  // namespace sewer3d
