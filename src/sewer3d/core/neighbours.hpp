#pragma once
/// \file
/// All pairs of 2-D points closer than a radius, as per-point neighbour lists.

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace sewer3d {

/// Neighbour lists in one flat array (CSR): point i's neighbours (itself excluded) are
/// indices[offsets[i] .. offsets[i + 1]). Built with a dense grid of radius-sized cells over
/// the points' bounding box, so each query looks at 3 x 3 cells.
struct NeighbourLists {
  std::vector<int> offsets;
  std::vector<int> indices;
  std::pair<const int*, const int*> Of(int i) const {
    return {indices.data() + offsets[i], indices.data() + offsets[i + 1]};
  }
};

/// `position(i)` gives point i for i in [0, count).
template <typename Position>
NeighbourLists RadiusNeighbours(int count, double radius, Position&& position);

template <typename Position>
NeighbourLists RadiusNeighbours(int count, double radius, Position&& position) {
  NeighbourLists out;
  out.offsets.assign(count + 1, 0);
  if (count == 0) return out;
  Eigen::Vector2d lo = position(0), hi = lo;
  for (int i = 1; i < count; ++i) lo = lo.cwiseMin(position(i)), hi = hi.cwiseMax(position(i));
  const int gx = static_cast<int>((hi.x() - lo.x()) / radius) + 1;
  const int gy = static_cast<int>((hi.y() - lo.y()) / radius) + 1;
  std::vector<int> cell_of(count), cell_start(static_cast<size_t>(gx) * gy + 1, 0), order(count);
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d p = position(i);
    cell_of[i] = static_cast<int>((p.y() - lo.y()) / radius) * gx +
                 static_cast<int>((p.x() - lo.x()) / radius);
    ++cell_start[cell_of[i] + 1];
  }
  for (size_t c = 1; c < cell_start.size(); ++c) cell_start[c] += cell_start[c - 1];
  std::vector<int> fill(cell_start.begin(), cell_start.end() - 1);
  for (int i = 0; i < count; ++i) order[fill[cell_of[i]]++] = i;
  const double r2 = radius * radius;
  out.indices.reserve(static_cast<size_t>(count) * 12);
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d p = position(i);
    const int cx = cell_of[i] % gx, cy = cell_of[i] / gx;
    for (int y = std::max(0, cy - 1); y <= std::min(gy - 1, cy + 1); ++y) {
      for (int x = std::max(0, cx - 1); x <= std::min(gx - 1, cx + 1); ++x) {
        const int c = y * gx + x;
        for (int k = cell_start[c]; k < cell_start[c + 1]; ++k) {
          const int j = order[k];
          if (j != i && (position(j) - p).squaredNorm() <= r2) out.indices.push_back(j);
        }
      }
    }
    out.offsets[i + 1] = static_cast<int>(out.indices.size());
  }
  return out;
}

}  // namespace sewer3d
