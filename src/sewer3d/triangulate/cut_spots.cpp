#include "sewer3d/triangulate/cut_spots.hpp"

#include <algorithm>

#include "sewer3d/core/check.hpp"
#include "sewer3d/triangulate/element_pixel_map.hpp"

namespace sewer3d {

void CutSpotOptions::Check() const {
  ValidateNotNegative("cut_spots.max_fit_tolerance", max_fit_tolerance);
  ValidatePositive("cut_spots.max_fit_px", max_fit_px);
  SEWER3D_VALIDATE(min_neighbours >= 4, "cut_spots.min_neighbours",
                   "must be at least 4 (three points only define the map), got " << min_neighbours);
  SEWER3D_VALIDATE(area_fraction > 0.0 && area_fraction <= 1.0, "cut_spots.area_fraction",
                   "must be in (0, 1], got " << area_fraction);
}

int RejectCutSpots(std::vector<TriangulatedPoint>& points,
                   const std::vector<CodedObservation>& observations, std::span<const int> area_px,
                   const ElementMesh& mesh, const NeighbourLists& neighbours, double tolerance_px,
                   const CutSpotOptions& options) {
  if (!options.enabled || points.empty()) return 0;
  // Per mesh cell: its point and its spot's area (−1 without), dense for the neighbour scans.
  const std::size_t cells = static_cast<std::size_t>(mesh.rows) * mesh.cols;
  std::vector<int> point_of(cells, -1), area_of(cells, -1);
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    const int cell = mesh.Index(points[i].row, points[i].col);
    if (cell < 0) continue;
    point_of[cell] = i;
    area_of[cell] = area_px[points[i].observation];
  }
  const double max_fit = std::max(options.max_fit_px, options.max_fit_tolerance * tolerance_px);
  std::vector<char> cut(points.size(), 0);
  std::vector<int> areas, ring;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    const int cell = mesh.Index(points[i].row, points[i].col);
    if (cell < 0) continue;
    const int own = area_of[cell];
    const auto [first, last] = neighbours.Of(cell);
    int largest = 0;
    for (const int* j = first; j != last; ++j) largest = std::max(largest, area_of[*j]);
    if (own >= options.area_fraction * largest) continue;  // most spots: not below the median
    areas.clear();
    for (const int* j = first; j != last; ++j)
      if (area_of[*j] >= 0) areas.push_back(area_of[*j]);
    const auto middle = areas.begin() + static_cast<std::ptrdiff_t>(areas.size() / 2);
    std::nth_element(areas.begin(), middle, areas.end());
    if (own >= options.area_fraction * *middle) continue;
    // The point itself left out of its neighbours' map: it may be the one off.
    TwoRing(neighbours, cell, ring);
    std::erase(ring, cell);
    const auto fit = FitElementPixelMap(ring, point_of, points, observations);
    cut[i] = fit && fit->points >= options.min_neighbours && fit->max_residual_px > max_fit;
  }
  int kept = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!cut[i]) points[kept++] = points[i];
  const int removed = static_cast<int>(points.size()) - kept;
  points.resize(kept);
  return removed;
}

}  // namespace sewer3d
