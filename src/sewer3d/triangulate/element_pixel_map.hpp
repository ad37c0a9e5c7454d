#pragma once
/// \file
/// Where a smooth surface puts the spots of neighbouring elements: an affine map from element
/// coordinates (column, row) to camera pixels, fitted to the points of a few neighbours. Its
/// largest residual says whether they lie on one smooth surface; across a depth step the
/// disparity jumps along the epipolar line and no affine map fits both sides.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sewer3d/core/neighbours.hpp"
#include "sewer3d/decode/decoder.hpp"
#include "sewer3d/triangulate/correspondences.hpp"

namespace sewer3d {

struct ElementPixelMap {
  Eigen::Matrix<double, 3, 2> map;  ///< pixel = (column, row, 1) · map
  double max_residual_px = 0.0;     ///< at the points it was fitted to
  int points = 0;                   ///< how many it was fitted to

  [[nodiscard]] Eigen::Vector2d At(double col, double row) const {
    return (Eigen::RowVector3d(col, row, 1.0) * map).transpose();
  }
};

/// Least squares over `points[point_of[cell]]` for the `cells` that have a point (point_of:
/// per mesh grid index, −1 without), their pixels from `observations`; nullopt when fewer
/// than three such points or all on one line.
std::optional<ElementPixelMap> FitElementPixelMap(
    const std::vector<int>& cells, const std::vector<int>& point_of,
    const std::vector<TriangulatedPoint>& points,
    const std::vector<CodedObservation>& observations);

/// The mesh grid indices among `cell`'s neighbours and their neighbours, sorted, without
/// duplicates (`cell` itself among them) into `ring`.
void TwoRing(const NeighbourLists& neighbours, int cell, std::vector<int>& ring);

}  // namespace sewer3d
