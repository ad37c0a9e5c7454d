#include "sewer3d/triangulate/correspondences.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/neighbours.hpp"
#include "sewer3d/core/union_find.hpp"
#include "sewer3d/triangulate/dlt.hpp"

namespace sewer3d {

void TriangulationOptions::Check() const {
  ValidatePositive("z_min_mm", z_min_mm);
  SEWER3D_VALIDATE(z_max_mm > z_min_mm, "z_max_mm",
                   "must be > z_min_mm (" << z_min_mm << "), got " << z_max_mm);
  ValidatePositive("max_reprojection_px", max_reprojection_px);
  ValidateNotNegative("adaptive_sigmas", adaptive_sigmas);
  ValidateNotNegative("max_adaptive_px", max_adaptive_px);
}

Triangulator::Triangulator(const ModuleDescription& module, int array_rows, int array_cols,
                           const TriangulationOptions& options)
    : module_(module),
      array_rows_(array_rows),
      array_cols_(array_cols),
      options_(options),
      camera_(module.camera),
      projector_(module.projector) {
  options_.Check();
  SEWER3D_CHECK(array_rows > 0 && array_cols > 0, "array size");
  p_projector_.leftCols<3>() = module.projector_from_camera.RotationMatrix();
  p_projector_.col(3) = module.projector_from_camera.translation;
  const PatternLayout& layout = module.pattern;
  element_cols_ = static_cast<int>(std::ceil(module.projector.width / layout.pitch_px)) + 1;
  element_rows_ = static_cast<int>(std::ceil(module.projector.height / layout.pitch_px)) + 1;
  element_xy_.assign(static_cast<size_t>(element_cols_) * element_rows_,
                     Eigen::Vector2d::Constant(std::nan("")));
  for (int r = 0; r < element_rows_; ++r) {
    for (int c = 0; c < element_cols_; ++c) {
      // Only elements whose whole disk the projector shows: the image edge cuts the others,
      // and a cut spot's centroid lies off its element's centre (a row of them along the
      // edge measured 0.8 mm deep once a calibrated geometry brought the edge into view).
      const Eigen::Vector2d centre = layout.ElementCentre(r, c);
      const double radius = 0.5 * layout.spot_diameter_px;
      const bool inside = centre.x() - radius >= -0.5 && centre.y() - radius >= -0.5 &&
                          centre.x() + radius <= module.projector.width - 0.5 &&
                          centre.y() + radius <= module.projector.height - 0.5;
      if (!inside) continue;
      if (const auto xy = projector_.Unproject(centre))
        element_xy_[static_cast<size_t>(r) * element_cols_ + c] = *xy;
    }
  }
}

const Eigen::Vector2d* Triangulator::Element(int r, int c) const {
  if (r < 0 || c < 0 || r >= element_rows_ || c >= element_cols_) return nullptr;
  const Eigen::Vector2d& xy = element_xy_[static_cast<size_t>(r) * element_cols_ + c];
  return std::isnan(xy.x()) ? nullptr : &xy;
}

std::optional<TriangulatedPoint> Triangulator::AtElement(int r, int c,
                                                         const Eigen::Vector2d& camera_px,
                                                         double gate_px, int observation) const {
  const auto xy = camera_.Unproject(camera_px);
  if (!xy) return std::nullopt;
  return AtElement(r, c, camera_px, *xy, gate_px, observation);
}

std::optional<TriangulatedPoint> Triangulator::AtElement(int r, int c,
                                                         const Eigen::Vector2d& camera_px,
                                                         const Eigen::Vector2d& xy, double gate_px,
                                                         int observation) const {
  const Eigen::Vector2d* projector_xy = Element(r, c);
  if (!projector_xy) return std::nullopt;
  const auto x = TriangulateOnProjectorRay(xy, *projector_xy, p_projector_);
  if (!x || x->z() < options_.z_min_mm || x->z() > options_.z_max_mm) return std::nullopt;
  const auto back_camera = camera_.Project(*x);
  const auto back_projector =
      projector_.Project(p_projector_.leftCols<3>() * *x + p_projector_.col(3));
  if (!back_camera || !back_projector) return std::nullopt;
  const double error = std::max((*back_camera - camera_px).norm(),
                                (*back_projector - module_.pattern.ElementCentre(r, c)).norm());
  if (error > gate_px) return std::nullopt;
  return TriangulatedPoint{observation, *x, r, c, error};
}

Triangulator::Candidates Triangulator::NearestTiles(int k, const CodedObservation& o,
                                                    double gate) const {
  Candidates found;
  const PatternLayout& layout = module_.pattern;
  const double pitch = layout.pitch_px;
  const TriangulationOptions& options = options_;
  const auto xy = camera_.Unproject(o.camera_px);
  if (!xy) return found;
  found.projectable = true;
  found.best.reprojection_px = 1e300;
  const Eigen::Vector3d ray(xy->x(), xy->y(), 1.0);
  // Projector region the epipolar curve covers over the depth range (sampled: distortion
  // bends it slightly).
  double u_lo = 1e300, u_hi = -1e300, v_lo = 1e300, v_hi = -1e300;
  for (int i = 0; i <= 2; ++i) {  // ends and middle; the one-pitch margin covers the bend
    const double inv_z =
        1.0 / options.z_max_mm + (1.0 / options.z_min_mm - 1.0 / options.z_max_mm) * i / 2.0;
    const auto uv =
        projector_.Project(p_projector_.leftCols<3>() * (ray / inv_z) + p_projector_.col(3));
    if (!uv) continue;
    u_lo = std::min(u_lo, uv->x()), u_hi = std::max(u_hi, uv->x());
    v_lo = std::min(v_lo, uv->y()), v_hi = std::max(v_hi, uv->y());
  }
  if (u_lo > u_hi) return found;
  // Element indices whose centres lie in the region (one pitch and the gate of margin),
  // congruent to the decoded position.
  const double margin = pitch + gate;
  auto first = [&](double lo, double offset, int mod, int period) {
    const int index = static_cast<int>(std::floor((lo - margin - offset + 0.5) / pitch - 0.5));
    return index + ((mod - index) % period + period) % period;
  };
  const int r_start = first(v_lo, layout.offset_px.y(), o.row_mod, array_rows_);
  const int c_start = first(u_lo, layout.offset_px.x(), o.col_mod, array_cols_);
  for (int r = r_start; layout.ElementCentre(r, 0).y() <= v_hi + margin; r += array_rows_) {
    for (int c = c_start; layout.ElementCentre(0, c).x() <= u_hi + margin; c += array_cols_) {
      const auto point = AtElement(r, c, o.camera_px, *xy, gate, k);
      if (!point) continue;
      if (point->reprojection_px < found.best.reprojection_px) {
        found.second_px = found.best.reprojection_px;
        found.best = *point;
      } else {
        found.second_px = std::min(found.second_px, point->reprojection_px);
      }
    }
  }
  return found;
}

namespace {

double AdaptiveTolerance(const TriangulationOptions& options, std::vector<double>& nearest_px) {
  const double floor = options.max_reprojection_px;
  // Too few spots say nothing about their scatter.
  constexpr size_t kMinSpots = 50;
  if (options.adaptive_sigmas <= 0.0 || nearest_px.size() < kMinSpots) return floor;
  const auto median_of = [](std::vector<double>& v) {
    const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), middle, v.end());
    return *middle;
  };
  // Distances to the lines are |b + N(0, σ)|: b the offset a module's calibration error
  // gives (a smooth field over the image), σ its spots' scatter. The median plus k robust
  // sigmas of the distances about it (MAD / 0.6745) is b + kσ where b dominates; for b = 0 (a
  // half-normal: median 0.6745 σ, MAD 0.40 σ) k is set to give adaptive_sigmas σ.
  const double median = median_of(nearest_px);
  for (double& d : nearest_px) d = std::abs(d - median);
  const double sigma = median_of(nearest_px) / 0.6745;
  const double k = (options.adaptive_sigmas - 0.6745) / (0.40 / 0.6745);
  const double wanted = median + k * sigma;
  // Spots that scatter beyond what a module's errors make do not fit the module (another
  // module's image, a shifted one: distances spread evenly up to the gate): widening would let
  // their chance decodes through.
  if (wanted > std::max(floor, options.max_adaptive_px)) return floor;
  return std::max(floor, wanted);
}

}  // namespace

std::vector<TriangulatedPoint> Triangulator::Triangulate(
    const std::vector<CodedObservation>& observations, TriangulationStats* stats) const {
  TriangulationStats local;
  TriangulationStats& st = stats ? *stats : local;
  const double gate = std::max(options_.max_reprojection_px,
                               options_.adaptive_sigmas > 0.0 ? options_.max_adaptive_px : 0.0);
  std::vector<Candidates> candidates(observations.size());
  std::vector<double> nearest_px;
  nearest_px.reserve(observations.size());
  for (size_t k = 0; k < observations.size(); ++k) {
    candidates[k] = NearestTiles(static_cast<int>(k), observations[k], gate);
    // Only unambiguous spots measure the scatter: a second tile within the gate may be the
    // right one.
    if (candidates[k].best.reprojection_px <= gate && candidates[k].second_px > gate)
      nearest_px.push_back(candidates[k].best.reprojection_px);
  }
  const double tolerance = AdaptiveTolerance(options_, nearest_px);
  st.tolerance_px = tolerance;
  std::vector<TriangulatedPoint> points;
  points.reserve(observations.size());
  for (const Candidates& c : candidates) {
    if (!c.projectable) {
      ++st.unprojectable;
    } else if (c.best.reprojection_px > tolerance) {
      ++st.no_element;
    } else if (c.second_px <= tolerance) {
      ++st.ambiguous;
    } else {
      points.push_back(c.best);
    }
  }
  return points;
}

std::vector<TriangulatedPoint> TriangulateObservations(
    const ModuleDescription& module, int array_rows, int array_cols,
    const std::vector<CodedObservation>& observations, const TriangulationOptions& options,
    TriangulationStats* stats) {
  return Triangulator(module, array_rows, array_cols, options).Triangulate(observations, stats);
}

void DepthOutlierOptions::Check() const {
  ValidatePositive("radius_px", radius_px);
  ValidateNotNegative("min_step_mm", min_step_mm);
  ValidateNotNegative("fraction", fraction);
  ValidateNotNegative("min_segment_points", min_segment_points);
}

namespace {

// Clears keep[i] of the kept points whose segment (kept neighbours joined where their depths
// differ by at most the step the test allows) has fewer than min_points points.
void DropSmallSegments(const std::vector<TriangulatedPoint>& points,
                       const NeighbourLists& neighbours, const DepthOutlierOptions& options,
                       std::vector<char>& keep) {
  const int n = static_cast<int>(points.size());
  UnionFind segments(n);
  for (int i = 0; i < n; ++i) {
    if (!keep[i]) continue;
    const double z = points[i].point_mm.z();
    const auto [first, last] = neighbours.Of(i);
    for (const int* j = first; j != last; ++j) {
      const double zj = points[*j].point_mm.z();
      const double step = std::max(options.min_step_mm, options.fraction * std::max(z, zj));
      if (keep[*j] && std::abs(z - zj) <= step) segments.Join(*j, i);
    }
  }
  std::vector<int> size(n, 0);
  for (int i = 0; i < n; ++i) size[segments.Root(i)] += keep[i];
  for (int i = 0; i < n; ++i) {
    if (keep[i] && size[segments.Root(i)] < options.min_segment_points) keep[i] = 0;
  }
}

}  // namespace

int RejectDepthOutliers(std::vector<TriangulatedPoint>& points,
                        const std::vector<CodedObservation>& observations,
                        const DepthOutlierOptions& options) {
  options.Check();
  const NeighbourLists neighbours = RadiusNeighbours(
      static_cast<int>(points.size()), options.radius_px, [&](int i) -> const Eigen::Vector2d& {
        return observations[points[i].observation].camera_px;
      });
  std::vector<char> keep(points.size(), 1);
  std::vector<double> depths;
  for (size_t i = 0; i < points.size(); ++i) {
    depths.clear();
    const auto [first, last] = neighbours.Of(static_cast<int>(i));
    for (const int* j = first; j != last; ++j) depths.push_back(points[*j].point_mm.z());
    if (depths.size() < 2) {  // an isolated decode has nothing to confirm it
      keep[i] = 0;
      continue;
    }
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    const double median = depths[depths.size() / 2];
    const double z = points[i].point_mm.z();
    if (std::abs(z - median) > std::max(options.min_step_mm, options.fraction * z)) keep[i] = 0;
  }
  DropSmallSegments(points, neighbours, options, keep);
  std::vector<TriangulatedPoint> kept;
  kept.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    if (keep[i]) kept.push_back(points[i]);
  }
  const int removed = static_cast<int>(points.size() - kept.size());
  points = std::move(kept);
  return removed;
}

int RejectSharedElements(std::vector<TriangulatedPoint>& points) {
  std::vector<std::pair<int, int>> elements;
  elements.reserve(points.size());
  for (const TriangulatedPoint& p : points) elements.emplace_back(p.row, p.col);
  std::sort(elements.begin(), elements.end());
  const auto shared = [&](const TriangulatedPoint& p) {
    const auto [first, last] =
        std::equal_range(elements.begin(), elements.end(), std::pair<int, int>(p.row, p.col));
    return last - first > 1;
  };
  const auto before = points.size();
  points.erase(std::remove_if(points.begin(), points.end(), shared), points.end());
  return static_cast<int>(before - points.size());
}

InconsistentPoints RejectInconsistentPoints(std::vector<TriangulatedPoint>& points,
                                            const std::vector<CodedObservation>& observations,
                                            const DepthOutlierOptions& options) {
  InconsistentPoints removed;
  removed.depth_outliers = RejectDepthOutliers(points, observations, options);
  removed.shared_elements = RejectSharedElements(points);
  return removed;
}

}  // namespace sewer3d
