#include "sewer3d/triangulate/element_pixel_map.hpp"

#include <Eigen/Dense>
#include <algorithm>

namespace sewer3d {

std::optional<ElementPixelMap> FitElementPixelMap(
    const std::vector<int>& cells, const std::vector<int>& point_of,
    const std::vector<TriangulatedPoint>& points,
    const std::vector<CodedObservation>& observations) {
  const auto count = static_cast<Eigen::Index>(cells.size());
  Eigen::Matrix<double, Eigen::Dynamic, 3> elements(count, 3);
  Eigen::Matrix<double, Eigen::Dynamic, 2> pixels(count, 2);
  Eigen::Index n = 0;
  for (const int j : cells) {
    if (point_of[j] < 0) continue;
    const TriangulatedPoint& p = points[point_of[j]];
    elements.row(n) << p.col, p.row, 1.0;
    pixels.row(n) = observations[p.observation].camera_px.transpose();
    ++n;
  }
  if (n < 3) return std::nullopt;
  elements.conservativeResize(n, 3);
  pixels.conservativeResize(n, 2);
  const Eigen::Matrix3d normal = elements.transpose() * elements;
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(normal);
  if (lu.rank() < 3) return std::nullopt;  // on one line
  ElementPixelMap fit;
  fit.map = lu.solve(elements.transpose() * pixels);
  fit.max_residual_px = (elements * fit.map - pixels).rowwise().norm().maxCoeff();
  fit.points = static_cast<int>(n);
  return fit;
}

void TwoRing(const NeighbourLists& neighbours, int cell, std::vector<int>& ring) {
  ring.clear();
  const auto [first, last] = neighbours.Of(cell);
  for (const int* j = first; j != last; ++j) {
    ring.push_back(*j);
    const auto [first2, last2] = neighbours.Of(*j);
    ring.insert(ring.end(), first2, last2);
  }
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
}

}  // namespace sewer3d
