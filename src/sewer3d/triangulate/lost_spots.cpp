#include "sewer3d/triangulate/lost_spots.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "sewer3d/core/check.hpp"
#include "sewer3d/decode/niblack.hpp"
#include "sewer3d/triangulate/element_pixel_map.hpp"

namespace sewer3d {
namespace {

constexpr double kSpotCell = 16.0;     // px, the bucket size of the binariser's spots
constexpr double kMinSpacingPx = 4.0;  // px, the least distance between neighbouring spots

}  // namespace

void LostSpotOptions::Check() const {
  SEWER3D_VALIDATE(min_neighbours >= 3, "lost_spots.min_neighbours",
                   "must be >= 3, got " << min_neighbours);
  ValidatePositive("lost_spots.max_fit_px", max_fit_px);
  ValidateNotNegative("lost_spots.max_fit_tolerance", max_fit_tolerance);
  ValidatePositive("lost_spots.step_fits", step_fits);
  SEWER3D_VALIDATE(max_offset > 0.0 && max_offset <= 0.3, "lost_spots.max_offset",
                   "must be in (0, 0.3], got " << max_offset);
  ValidateNotNegative("lost_spots.max_rounds", max_rounds);
  spot.Check();
}

LostSpotFinder::LostSpotFinder(const ElementMesh& mesh, int array_rows, int array_cols,
                               const LostSpotOptions& options)
    : neighbours_(MeshNeighbours(mesh)),
      array_rows_(array_rows),
      array_cols_(array_cols),
      options_(options) {
  options_.Check();
  grid_.row0 = mesh.row0;
  grid_.col0 = mesh.col0;
  grid_.rows = mesh.rows;
  grid_.cols = mesh.cols;
}

bool LostSpotFinder::StepNearby(const Eigen::Matrix<double, 3, 2>& map, double limit_px,
                                const std::vector<CodedObservation>& observations,
                                const std::vector<TriangulatedPoint>& points) const {
  outer_.clear();
  for (const int j : ring_) {
    const auto [first, last] = neighbours_.Of(j);
    outer_.insert(outer_.end(), first, last);
  }
  std::sort(outer_.begin(), outer_.end());
  outer_.erase(std::unique(outer_.begin(), outer_.end()), outer_.end());
  for (const int j : outer_) {
    if (point_of_[j] < 0) continue;
    const TriangulatedPoint& p = points[point_of_[j]];
    const Eigen::Vector2d at = (Eigen::RowVector3d(p.col, p.row, 1.0) * map).transpose();
    if ((at - observations[p.observation].camera_px).norm() > limit_px) return true;
  }
  return false;
}

bool LostSpotFinder::NearDetectedSpot(const Eigen::Vector2d& px, double radius) const {
  const int x0 = std::max(0, static_cast<int>((px.x() - radius) / kSpotCell));
  const int x1 = std::min(spot_grid_cols_ - 1, static_cast<int>((px.x() + radius) / kSpotCell));
  const int y0 = std::max(0, static_cast<int>((px.y() - radius) / kSpotCell));
  const int y1 = std::min(spot_grid_rows_ - 1, static_cast<int>((px.y() + radius) / kSpotCell));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const int cell = y * spot_grid_cols_ + x;
      for (int k = spot_start_[cell]; k < spot_start_[cell + 1]; ++k)
        if ((spot_px_[k] - px).squaredNorm() <= radius * radius) return true;
    }
  }
  return false;
}

std::optional<LostSpotFinder::Found> LostSpotFinder::Look(
    int cell, const cv::Mat& image, double level_scale, const Triangulator& triangulator,
    double tolerance_px, const std::vector<CodedObservation>& observations,
    const std::vector<TriangulatedPoint>& points) const {
  // The points among the element's mesh neighbours and theirs: a patch's edge has points on
  // one side only, three or so among the neighbours.
  TwoRing(neighbours_, cell, ring_);
  const auto [first, last] = neighbours_.Of(cell);
  const auto fit = FitElementPixelMap(ring_, point_of_, points, observations);
  if (!fit || fit->points < options_.min_neighbours) return std::nullopt;
  const Eigen::Matrix<double, 3, 2>& map = fit->map;
  const double max_fit = std::max(options_.max_fit_px, options_.max_fit_tolerance * tolerance_px);
  if (fit->max_residual_px > max_fit) return std::nullopt;
  if (StepNearby(map, options_.step_fits * max_fit, observations, points)) return std::nullopt;
  const int r = grid_.row0 + cell / grid_.cols, c = grid_.col0 + cell % grid_.cols;
  const Eigen::Vector2d at = (Eigen::RowVector3d(c, r, 1.0) * map).transpose();
  // Distance to the nearest neighbour's spot, as the map puts it (lost or not).
  double spacing = 1e300;
  for (const int* j = first; j != last; ++j) {
    const int rj = grid_.row0 + *j / grid_.cols, cj = grid_.col0 + *j % grid_.cols;
    spacing = std::min(spacing, ((Eigen::RowVector3d(cj, rj, 1.0) * map).transpose() - at).norm());
  }
  // Spots closer than a few pixels are not told apart (nor is a map that folds its grid).
  if (!(spacing >= kMinSpacingPx) || !at.allFinite()) return std::nullopt;
  if (NearDetectedSpot(at, 0.5 * spacing)) return std::nullopt;
  const auto spot =
      FaintSpotAt(image, level_scale, at, 0.3 * spacing, 0.5 * spacing, options_.spot);
  // Off the prediction by at most what the frame's spots scatter about their epipolar lines
  // (the same speckle, placement and calibration error move them along the line), and never
  // toward a neighbour's place.
  const double max_offset = std::min(options_.max_offset * spacing, tolerance_px);
  if (!spot || (spot->centre_px - at).norm() > max_offset) return std::nullopt;
  Found found{cell,
              {spot->centre_px, ((r % array_rows_) + array_rows_) % array_rows_,
               ((c % array_cols_) + array_cols_) % array_cols_},
              {}};
  const auto point = triangulator.AtElement(r, c, spot->centre_px, tolerance_px, 0);
  if (!point) return std::nullopt;
  found.point = *point;
  return found;
}

int LostSpotFinder::Find(const cv::Mat& image, const std::vector<Spot>& spots,
                         const Triangulator& triangulator, double tolerance_px,
                         std::vector<CodedObservation>& observations,
                         std::vector<TriangulatedPoint>& points) {
  if (!options_.enabled || points.empty()) return 0;
  point_of_.assign(static_cast<std::size_t>(grid_.rows) * grid_.cols, -1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int cell = grid_.Index(points[i].row, points[i].col);
    if (cell >= 0) point_of_[cell] = static_cast<int>(i);
  }
  spot_grid_cols_ = static_cast<int>(image.cols / kSpotCell) + 1;
  spot_grid_rows_ = static_cast<int>(image.rows / kSpotCell) + 1;
  spot_start_.assign(static_cast<std::size_t>(spot_grid_cols_) * spot_grid_rows_ + 1, 0);
  const auto bucket = [&](const Spot& s) {
    const int x = std::clamp(static_cast<int>(s.centre_px.x() / kSpotCell), 0, spot_grid_cols_ - 1);
    const int y = std::clamp(static_cast<int>(s.centre_px.y() / kSpotCell), 0, spot_grid_rows_ - 1);
    return y * spot_grid_cols_ + x;
  };
  for (const Spot& s : spots) ++spot_start_[bucket(s) + 1];
  for (std::size_t k = 1; k < spot_start_.size(); ++k) spot_start_[k] += spot_start_[k - 1];
  spot_px_.resize(spots.size());
  std::vector<int> fill(spot_start_.begin(), spot_start_.end() - 1);
  for (const Spot& s : spots) spot_px_[fill[bucket(s)]++] = s.centre_px;

  // Candidates: lit cells without a point next to cells with one.
  std::vector<int> frontier;
  for (const TriangulatedPoint& p : points) {
    const int cell = grid_.Index(p.row, p.col);
    if (cell < 0) continue;
    const auto [first, last] = neighbours_.Of(cell);
    for (const int* j = first; j != last; ++j)
      if (point_of_[*j] < 0) frontier.push_back(*j);
  }
  const double level_scale = NiblackBinariser::LevelScale(image);
  int added = 0;
  std::vector<Found> round;
  for (int k = 0; k < options_.max_rounds && !frontier.empty(); ++k) {
    std::sort(frontier.begin(), frontier.end());
    frontier.erase(std::unique(frontier.begin(), frontier.end()), frontier.end());
    round.clear();
    for (const int cell : frontier) {
      if (point_of_[cell] >= 0) continue;
      if (auto f = Look(cell, image, level_scale, triangulator, tolerance_px, observations, points))
        round.push_back(*f);
    }
    frontier.clear();
    for (Found& f : round) {
      f.point.observation = static_cast<int>(observations.size());
      observations.push_back(f.observation);
      point_of_[f.cell] = static_cast<int>(points.size());
      points.push_back(f.point);
      const auto [first, last] = neighbours_.Of(f.cell);
      for (const int* j = first; j != last; ++j)
        if (point_of_[*j] < 0) frontier.push_back(*j);
    }
    added += static_cast<int>(round.size());
  }
  return added;
}

}  // namespace sewer3d
