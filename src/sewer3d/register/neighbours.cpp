#include "sewer3d/register/neighbours.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

// A node's footprint on the mock-up cylinder: wall points (model frame) and their z range.
struct Footprint {
  std::vector<Eigen::Vector3d> wall;
  double z_min = std::numeric_limits<double>::infinity();
  double z_max = -std::numeric_limits<double>::infinity();
};

// Exit point of the ray o + s d (s > 0) through the cylinder ρ = radius about the axis along z
// through `axis`: the larger root of |o_xy − axis + s d_xy|² = radius².
std::optional<Eigen::Vector3d> HitCylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                           const Eigen::Vector2d& axis, double radius) {
  const Eigen::Vector2d q = o.head<2>() - axis;
  const Eigen::Vector2d e = d.head<2>();
  const double a = e.squaredNorm();
  if (a < 1e-12) return std::nullopt;  // ray along the axis
  const double b = q.dot(e), c = q.squaredNorm() - radius * radius;
  const double disc = b * b - a * c;
  if (disc < 0.0) return std::nullopt;
  const double s = (-b + std::sqrt(disc)) / a;
  if (!(s > 0.0)) return std::nullopt;
  return o + s * d;
}

Footprint CastFootprint(const AcquisitionNode& node, const CameraModel& camera,
                        const NeighbourOptions& options) {
  Footprint f;
  const CameraIntrinsics& in = camera.intrinsics();
  const double radius = 0.5 * options.nominal_diameter_mm;
  const int step = options.grid_step_px;
  for (int v = step / 2; v < in.height; v += step) {
    for (int u = step / 2; u < in.width; u += step) {
      const auto ray = camera.Ray(Eigen::Vector2d(u, v));
      if (!ray) continue;
      const auto hit =
          HitCylinder(node.world_from_camera.translation, node.world_from_camera.rotation * *ray,
                      options.axis_in_model_mm, radius);
      if (!hit) continue;
      f.wall.push_back(*hit);
      f.z_min = std::min(f.z_min, hit->z());
      f.z_max = std::max(f.z_max, hit->z());
    }
  }
  return f;
}

// Fraction of `wall` (model frame) inside the image of the camera at world_from_camera.
double VisibleFraction(const std::vector<Eigen::Vector3d>& wall, const Rigid3d& world_from_camera,
                       const CameraModel& camera) {
  if (wall.empty()) return 0.0;
  const Rigid3d camera_from_world = world_from_camera.Inverse();
  const CameraIntrinsics& in = camera.intrinsics();
  int seen = 0;
  for (const Eigen::Vector3d& p : wall) {
    const auto px = camera.Project(camera_from_world * p);
    if (px && px->x() >= -0.5 && px->y() >= -0.5 && px->x() <= in.width - 0.5 &&
        px->y() <= in.height - 0.5)
      ++seen;
  }
  return static_cast<double>(seen) / static_cast<double>(wall.size());
}

std::optional<PairKind> KindOf(const AcquisitionNode& a, const AcquisitionNode& b, int modules,
                               const NeighbourOptions& options) {
  if (a.module == b.module) {
    const int gap = std::abs(a.counter - b.counter);
    if (options.along && gap >= 1 && gap <= options.max_counter_gap) return PairKind::kAlong;
    return std::nullopt;
  }
  const int d = ((a.module - b.module) % modules + modules) % modules;
  if (options.around && (d == 1 || d == modules - 1)) return PairKind::kAround;
  return std::nullopt;
}

}  // namespace

const char* PairKindName(PairKind kind) { return kind == PairKind::kAlong ? "along" : "around"; }

void NeighbourOptions::Check() const {
  ValidatePositive("nominal_diameter_mm", nominal_diameter_mm);
  SEWER3D_VALIDATE(axis_in_model_mm.allFinite(), "axis_in_model_mm", "must be finite");
  SEWER3D_VALIDATE(grid_step_px >= 1, "grid_step_px", "must be >= 1, got " << grid_step_px);
  SEWER3D_VALIDATE(min_overlap >= 0.0 && min_overlap <= 1.0, "min_overlap",
                   "must lie in [0, 1], got " << min_overlap);
  SEWER3D_VALIDATE(max_counter_gap >= 1, "max_counter_gap",
                   "must be >= 1, got " << max_counter_gap);
  ValidateNotNegative("station_margin_mm", station_margin_mm);
}

NeighbourResult FindNeighbours(const std::vector<AcquisitionNode>& nodes, const Rig& rig,
                               const NeighbourOptions& options) {
  options.Check();
  const int modules = static_cast<int>(rig.modules.size());
  std::vector<CameraModel> cameras;
  for (const RigModule& m : rig.modules) cameras.emplace_back(m.module.camera);
  NeighbourResult out;
  out.report.nodes = static_cast<int>(nodes.size());
  std::vector<Footprint> footprints;
  for (const AcquisitionNode& node : nodes) {
    SEWER3D_VALIDATE(node.module >= 0 && node.module < modules, "module",
                     "is " << node.module << ", the rig has " << modules);
    footprints.push_back(CastFootprint(node, cameras[node.module], options));
    if (footprints.back().wall.empty()) ++out.report.nodes_without_wall;
  }
  for (size_t i = 0; i < nodes.size(); ++i) {
    for (size_t j = i + 1; j < nodes.size(); ++j) {
      const auto kind = KindOf(nodes[i], nodes[j], modules, options);
      const Footprint &fa = footprints[i], &fb = footprints[j];
      if (!kind || fa.wall.empty() || fb.wall.empty()) continue;
      if (fa.z_max + options.station_margin_mm < fb.z_min ||
          fb.z_max + options.station_margin_mm < fa.z_min)
        continue;
      ++out.report.candidates;
      NeighbourPair pair;
      pair.a = static_cast<int>(i);
      pair.b = static_cast<int>(j);
      pair.kind = *kind;
      pair.overlap_ab =
          VisibleFraction(fa.wall, nodes[j].world_from_camera, cameras[nodes[j].module]);
      pair.overlap_ba =
          VisibleFraction(fb.wall, nodes[i].world_from_camera, cameras[nodes[i].module]);
      if (pair.Overlap() >= options.min_overlap && pair.Overlap() > 0.0) {
        out.pairs.push_back(pair);
      } else {
        ++out.report.rejected_overlap;
      }
    }
  }
  out.report.kept = static_cast<int>(out.pairs.size());
  return out;
}

}  // namespace sewer3d
