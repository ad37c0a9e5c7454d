#include "sewer3d/sim/scene.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/root.hpp"

namespace sewer3d {
namespace {

// Orthonormal frame of a cylinder: e1 = camera z made perpendicular to the axis (clock 0),
// e2 = axis x e1 ... chosen so that clock increases toward camera +x.
struct CylinderFrame {
  Eigen::Vector3d a, e1, e2, c;
  double radius;
};

CylinderFrame FrameOf(const Scene& s) {
  CylinderFrame f;
  f.a = s.axis.normalized();
  f.c = s.axis_point_mm;
  f.e1 = (Eigen::Vector3d::UnitZ() - f.a.z() * f.a).normalized();
  f.e2 = f.a.cross(f.e1);
  if (f.e2.dot(Eigen::Vector3d::UnitX()) < 0) f.e2 = -f.e2;
  f.radius = 0.5 * s.diameter_mm;
  return f;
}

// Far root of |w⊥ + t d⊥| = r (origin inside the cylinder).
std::optional<double> CylinderRoot(const CylinderFrame& f, const Eigen::Vector3d& o,
                                   const Eigen::Vector3d& d, double r) {
  const Eigen::Vector3d w = o - f.c;
  const Eigen::Vector3d wp = w - w.dot(f.a) * f.a, dp = d - d.dot(f.a) * f.a;
  const double A = dp.squaredNorm(), B = 2.0 * wp.dot(dp), C = wp.squaredNorm() - r * r;
  const double disc = B * B - 4.0 * A * C;
  if (A <= 0.0 || disc < 0.0) return std::nullopt;
  const double t = (-B + std::sqrt(disc)) / (2.0 * A);
  if (!(t > 0.0)) return std::nullopt;
  return t;
}

// Cylinder coordinates of a point: clock angle (rad), station (mm), distance from the axis.
void ToCylinder(const CylinderFrame& f, const Eigen::Vector3d& x, double& clock, double& station,
                double& rho) {
  const Eigen::Vector3d w = x - f.c;
  station = w.dot(f.a);
  const Eigen::Vector3d radial = w - station * f.a;
  rho = radial.norm();
  clock = std::atan2(radial.dot(f.e2), radial.dot(f.e1));
}

std::optional<SurfaceHit> IntersectPlane(const Scene& s, const Eigen::Vector3d& o,
                                         const Eigen::Vector3d& d) {
  const Eigen::Vector3d n =
      Eigen::AngleAxisd(DegToRad(s.tilt_deg), Eigen::Vector3d::UnitX()) * Eigen::Vector3d(0, 0, -1);
  const Eigen::Vector3d p0(0.0, 0.0, s.distance_mm);
  const double denom = d.dot(n);
  if (std::abs(denom) < 1e-15) return std::nullopt;
  const double t = (p0 - o).dot(n) / denom;
  if (!(t > 0.0)) return std::nullopt;
  SurfaceHit hit;
  hit.t = t;
  hit.point = o + t * d;
  hit.normal = denom < 0 ? n : -n;
  // In-plane coordinates: camera x and the tilted y direction.
  const Eigen::Vector3d ey = n.cross(Eigen::Vector3d::UnitX()).normalized();
  hit.surface_mm = {hit.point.x(), (hit.point - p0).dot(ey)};
  hit.material = s.material;
  return hit;
}

}  // namespace

void Scene::Check() const {
  // Field names as in scene files (docs/simulator.md).
  // The ranges of `simulate frame`'s flags: a camera sees walls from centimetres to metres.
  SEWER3D_VALIDATE(type != Type::kPlane || (distance_mm >= 10.0 && distance_mm <= 5000.0),
                   "distance_mm", "must be 10 to 5000 mm, got " << distance_mm);
  SEWER3D_VALIDATE(std::abs(tilt_deg) < 89.0, "tilt_deg",
                   "must be within ±89 (exclusive), got " << tilt_deg);
  SEWER3D_VALIDATE(type == Type::kPlane || (diameter_mm >= 20.0 && diameter_mm <= 5000.0),
                   "diameter_mm", "must be 20 to 5000 mm, got " << diameter_mm);
  // Its norm must be finite too: (0, 1e308, 1e308) overflows when normalised.
  SEWER3D_VALIDATE(axis.allFinite() && axis.norm() > 0.0 && std::isfinite(axis.norm()), "axis",
                   "must be a finite, non-zero direction");
  SEWER3D_VALIDATE(axis_point_mm.allFinite() && axis_point_mm.norm() < 1e7, "axis_point_mm",
                   "must be finite and within 1e7 mm");
  SEWER3D_VALIDATE(type == Type::kPlane || std::abs(axis.normalized().z()) < 0.99, "axis",
                   "must not run (nearly) along the camera's optical axis");
  if (type != Type::kPlane) {
    const CylinderFrame f = FrameOf(*this);
    const Eigen::Vector3d w = -f.c;
    const double rho = (w - w.dot(f.a) * f.a).norm();
    SEWER3D_VALIDATE(rho < f.radius, "axis_point_mm",
                     "puts the camera outside the cylinder (decentring " << rho << " mm, radius "
                                                                         << f.radius << " mm)");
  }
  SEWER3D_VALIDATE(type == Type::kPipeWall || features.empty(), "features",
                   "only a pipe_wall scene has features (a plane or cylinder is plain)");
  SEWER3D_VALIDATE(features.size() <= PipeFeature::kMaxCount, "features",
                   "at most " << PipeFeature::kMaxCount << " features, got " << features.size());
  for (size_t i = 0; i < features.size(); ++i) {
    using T = PipeFeature::Type;
    const PipeFeature& ft = features[i];
    const std::string field = "features[" + std::to_string(i) + "].";
    SEWER3D_VALIDATE(
        ft.type == T::kJointStep || ft.type == T::kBump || ft.type == T::kPit ||
            ft.type == T::kCrack || ft.type == T::kWet,
        field + "type",
        "must be joint, bump, pit, crack or wet, got "
            << PipeFeatureTypeName(ft.type)
            << " (connections, spalling and deposits need a pipe world: simulate run)");
    CheckWithin(field, [&] { ft.CheckInPipe(diameter_mm); });
  }
  // Joint steps add up along the wall: together they are held to one joint's limit.
  double steps_mm = 0.0;
  for (const PipeFeature& ft : features)
    if (ft.type == PipeFeature::Type::kJointStep) steps_mm += std::abs(ft.offset_mm);
  SEWER3D_VALIDATE(steps_mm <= 0.2 * diameter_mm, "features",
                   "the joints' offsets add up to " << steps_mm << " mm, more than a fifth of the Ø"
                                                    << diameter_mm
                                                    << " pipe (the wall beyond them would leave "
                                                       "the pipe)");
}

double WallDisplacementMm(const Scene& scene, double clock_rad, double station_mm) {
  return AddPipeFeatures(
      0.0, scene.features, scene.material_seed, 0.5 * scene.diameter_mm, station_mm,
      [clock_rad] { return clock_rad; }, nullptr);
}

double DistanceToSurfaceMm(const Scene& scene, const Eigen::Vector3d& point) {
  if (scene.type == Scene::Type::kPlane) {
    const Eigen::Vector3d n =
        Eigen::AngleAxisd(DegToRad(scene.tilt_deg), Eigen::Vector3d::UnitX()) *
        Eigen::Vector3d(0, 0, -1);
    return std::abs(n.dot(point - Eigen::Vector3d(0.0, 0.0, scene.distance_mm)));
  }
  const CylinderFrame f = FrameOf(scene);
  double clock, station, rho;
  ToCylinder(f, point, clock, station, rho);
  if (scene.type == Scene::Type::kCylinder || scene.features.empty())
    return std::abs(rho - f.radius);
  // Displaced wall: the shortest distance to the wall profile along the axis and around it
  // within ±kReach, counting the vertical faces of steps (joint gaps and offsets), where the
  // radial distance alone would be wrong by the step's height.
  constexpr double kReach = 3.0, kStep = 0.05;
  const int n = static_cast<int>(kReach / kStep);
  double best = std::abs(rho - (f.radius - WallDisplacementMm(scene, clock, station)));
  for (int axis = 0; axis < 2; ++axis) {
    double previous = NAN;
    for (int k = -n; k <= n; ++k) {
      const double along = k * kStep;
      const double wall = axis == 0
                              ? f.radius - WallDisplacementMm(scene, clock, station + along)
                              : f.radius - WallDisplacementMm(scene, clock + along / rho, station);
      best = std::min(best, std::hypot(along, rho - wall));
      // A face between two samples whose walls straddle the point's radius.
      if (k > -n && (rho - previous) * (rho - wall) < 0.0)
        best = std::min(best, std::abs(along - 0.5 * kStep));
      previous = wall;
    }
  }
  return best;
}

std::optional<SurfaceHit> Intersect(const Scene& scene, const Eigen::Vector3d& o,
                                    const Eigen::Vector3d& d) {
  if (scene.type == Scene::Type::kPlane) return IntersectPlane(scene, o, d);
  const CylinderFrame f = FrameOf(scene);
  SurfaceHit hit;
  if (scene.type == Scene::Type::kCylinder || scene.features.empty()) {
    const auto t = CylinderRoot(f, o, d, f.radius);
    if (!t) return std::nullopt;
    hit.t = *t;
  } else {
    // Displaced wall: radius(clock, station) = R − δ. Bracket between the extreme radii and
    // refine g(t) = ρ(t) − radius(t) by the Illinois variant of regula falsi.
    double max_in = 0.0, max_out = 0.0;
    for (const auto& ft : scene.features) {
      const double h = ft.type == PipeFeature::Type::kBump ? ft.height_mm : ft.depth_mm;
      max_in += std::max({h, std::abs(ft.offset_mm), 0.0});
      max_out += std::max(h, 0.0) + std::abs(ft.offset_mm);
    }
    auto g = [&](double t) {
      double clock, station, rho;
      ToCylinder(f, o + t * d, clock, station, rho);
      return rho - (f.radius - WallDisplacementMm(scene, clock, station));
    };
    const auto lo_t = CylinderRoot(f, o, d, std::max(1e-3, f.radius - max_in - 1e-6));
    const auto hi_t = CylinderRoot(f, o, d, f.radius + max_out + 1e-6);
    if (!lo_t || !hi_t) return std::nullopt;
    double a = *lo_t, b = *hi_t, ga = g(a), gb = g(b);
    if (ga > 0.0) {
      hit.t = a;
    } else {
      hit.t = IllinoisRoot(g, a, b, ga, gb, 1e-9);
    }
  }
  hit.point = o + hit.t * d;
  double clock, station, rho;
  ToCylinder(f, hit.point, clock, station, rho);
  const Eigen::Vector3d radial_dir = std::cos(clock) * f.e1 + std::sin(clock) * f.e2;
  Eigen::Vector3d normal = -radial_dir;  // facing the axis
  if (scene.type == Scene::Type::kPipeWall && !scene.features.empty()) {
    // Tilt the normal by the displacement gradient (central differences, 0.05 mm).
    constexpr double h = 0.05;
    const double dd_ds = (WallDisplacementMm(scene, clock, station + h) -
                          WallDisplacementMm(scene, clock, station - h)) /
                         (2 * h);
    const double dd_darc = (WallDisplacementMm(scene, clock + h / rho, station) -
                            WallDisplacementMm(scene, clock - h / rho, station)) /
                           (2 * h);
    const Eigen::Vector3d tangent = -std::sin(clock) * f.e1 + std::cos(clock) * f.e2;
    normal = (normal - dd_ds * f.a - dd_darc * tangent).normalized();
  }
  hit.normal = normal.dot(d) < 0 ? normal : -normal;
  hit.surface_mm = {clock * f.radius, station};
  hit.material = scene.material;
  hit.film =
      WetCover(scene.features, scene.material_seed, f.radius, station, [clock] { return clock; });
  return hit;
}

}  // namespace sewer3d
