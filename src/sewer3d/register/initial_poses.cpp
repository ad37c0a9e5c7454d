#include "sewer3d/register/initial_poses.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <set>
#include <vector>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

// Odometry distance at t, the nearest reading's outside the readings' span.
double DistanceAt(const std::vector<OdometryReading>& odometry, double time_s, bool* outside) {
  if (const auto d = OdometryDistanceAt(odometry, time_s)) return *d;
  *outside = true;
  return time_s < odometry.front().time_s ? odometry.front().distance_mm
                                          : odometry.back().distance_mm;
}

struct Circle {
  Eigen::Vector2d centre;
  double radius = 0.0;
};

// Kåsa: x² + y² + D x + E y + F = 0 in least squares.
std::optional<Circle> AlgebraicCircle(const std::vector<Eigen::Vector2d>& p) {
  Eigen::MatrixXd a(p.size(), 3);
  Eigen::VectorXd b(p.size());
  for (size_t i = 0; i < p.size(); ++i) {
    a.row(i) << p[i].x(), p[i].y(), 1.0;
    b(i) = -p[i].squaredNorm();
  }
  const Eigen::Vector3d x = a.colPivHouseholderQr().solve(b);
  const Eigen::Vector2d centre(-0.5 * x(0), -0.5 * x(1));
  const double r2 = centre.squaredNorm() - x(2);
  if (!(r2 > 0.0) || !x.allFinite()) return std::nullopt;
  return Circle{centre, std::sqrt(r2)};
}

// Gauss–Newton on r_i = |p_i − c| − R.
Circle GeometricCircle(const std::vector<Eigen::Vector2d>& p, Circle c, int iterations) {
  for (int it = 0; it < iterations; ++it) {
    Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (const Eigen::Vector2d& q : p) {
      const Eigen::Vector2d d = q - c.centre;
      const double n = d.norm();
      if (n <= 0.0) continue;
      const Eigen::Vector3d j(-d.x() / n, -d.y() / n, -1.0);
      h += j * j.transpose();
      g += j * (n - c.radius);
    }
    const Eigen::Vector3d step = -h.ldlt().solve(g);
    if (!step.allFinite()) break;
    c.centre += step.head<2>();
    c.radius += step(2);
    if (step.norm() < 1e-9) break;
  }
  return c;
}

double Residual(const Eigen::Vector2d& p, const Circle& c) {
  return std::abs((p - c.centre).norm() - c.radius);
}

// Indices of the points within `band` of the circle.
std::vector<size_t> Within(const std::vector<Eigen::Vector2d>& p, const Circle& c, double band) {
  std::vector<size_t> out;
  for (size_t i = 0; i < p.size(); ++i)
    if (Residual(p[i], c) <= band) out.push_back(i);
  return out;
}

std::vector<Eigen::Vector2d> Select(const std::vector<Eigen::Vector2d>& p,
                                    const std::vector<size_t>& indices) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(indices.size());
  for (size_t i : indices) out.push_back(p[i]);
  return out;
}

// σ of the residuals of the indexed points from their median absolute value (1.4826 MAD).
double RobustSigma(const std::vector<Eigen::Vector2d>& p, const std::vector<size_t>& indices,
                   const Circle& c) {
  std::vector<double> r;
  r.reserve(indices.size());
  for (size_t i : indices) r.push_back(Residual(p[i], c));
  const auto middle = r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2);
  std::nth_element(r.begin(), middle, r.end());
  return 1.4826 * *middle;
}

}  // namespace

InitialPosesResult InitialPoses(const CaptureRun& run) {
  SEWER3D_VALIDATE(!run.odometry.empty(), "odometry", "has no reading");
  SEWER3D_VALIDATE(!run.images.empty(), "images", "the run has no image");
  InitialPosesResult out;
  InitialPosesReport& report = out.report;
  for (size_t i = 1; i < run.odometry.size(); ++i)
    if (run.odometry[i].distance_mm < run.odometry[i - 1].distance_mm) ++report.odometry_backwards;
  for (const OdometryReversal& r : run.odometry_findings.reversals)
    report.odometry_dropped += r.readings;
  double t0 = run.images.front().time_s;
  for (const RunImage& image : run.images) t0 = std::min(t0, image.time_s);
  report.first_image_time_s = t0;
  bool ignored = false;
  const double d0 = DistanceAt(run.odometry, t0, &ignored);

  const std::vector<Acquisition> acquisitions = GroupAcquisitions(run.images);
  report.acquisitions = static_cast<int>(acquisitions.size());
  for (const Acquisition& acq : acquisitions) {
    SEWER3D_VALIDATE(acq.module >= 0 && acq.module < static_cast<int>(run.rig.modules.size()),
                     "module",
                     "image of module " << acq.module << " but the rig has "
                                        << run.rig.modules.size() << " modules");
    const int image = acq.Image(ImageKind::kPattern);
    if (image < 0) {
      ++report.without_pattern;
      continue;
    }
    AcquisitionNode node;
    node.module = acq.module;
    node.counter = acq.counter;
    node.time_s = run.images[image].time_s;
    bool outside = false;
    node.distance_mm = DistanceAt(run.odometry, node.time_s, &outside) - d0;
    if (outside) ++report.outside_odometry;
    const OdometryUncertainty u = OdometryUncertaintyAt(run.odometry_findings, node.time_s);
    node.distance_sigma_mm = u.sigma_mm;
    node.speed_sigma_mm_s = u.speed_sigma_mm_s;
    if (u.gap != nullptr) ++report.in_odometry_gap;
    const Rigid3d world_from_carrier(Eigen::Quaterniond::Identity(),
                                     Eigen::Vector3d(0.0, 0.0, node.distance_mm));
    const Rigid3d& carrier_from_camera = run.rig.modules[acq.module].carrier_from_camera;
    node.world_from_camera = world_from_carrier * carrier_from_camera;
    if (const auto down = InclinometerDownAt(run.inclinometer, node.time_s)) {
      node.down_in_camera = carrier_from_camera.rotation.conjugate() * *down;
      ++report.with_inclinometer;
    }
    out.nodes.push_back(node);
  }
  report.nodes = static_cast<int>(out.nodes.size());
  return out;
}

void CarrierOffsetOptions::Check() const {
  SEWER3D_VALIDATE(min_points >= 3, "min_points", "must be >= 3, got " << min_points);
  SEWER3D_VALIDATE(min_modules >= 1, "min_modules", "must be >= 1, got " << min_modules);
  SEWER3D_VALIDATE(iterations >= 0, "iterations", "must be >= 0, got " << iterations);
  ValidatePositive("outlier_mm", outlier_mm);
  SEWER3D_VALIDATE(trim_rounds >= 0, "trim_rounds", "must be >= 0, got " << trim_rounds);
  ValidatePositive("trim_band_mm", trim_band_mm);
}

CarrierOffsetEstimate EstimateCarrierOffset(const Rig& rig,
                                            const std::vector<ModuleWallPoints>& walls,
                                            const CarrierOffsetOptions& options) {
  options.Check();
  std::vector<Eigen::Vector2d> points;
  std::vector<double> z;
  std::set<int> modules;
  for (const ModuleWallPoints& wall : walls) {
    SEWER3D_VALIDATE(wall.module >= 0 && wall.module < static_cast<int>(rig.modules.size()),
                     "module", "is " << wall.module << ", the rig has " << rig.modules.size());
    const Rigid3d& carrier_from_camera = rig.modules[wall.module].carrier_from_camera;
    for (const Eigen::Vector3d& p : wall.points_in_camera) {
      if (!p.allFinite()) continue;
      const Eigen::Vector3d in_carrier = carrier_from_camera * p;
      points.push_back(in_carrier.head<2>());
      z.push_back(in_carrier.z());
      modules.insert(wall.module);
    }
  }
  CarrierOffsetEstimate out;
  out.modules = static_cast<int>(modules.size());
  if (static_cast<int>(points.size()) < options.min_points || out.modules < options.min_modules)
    return out;
  const auto first = AlgebraicCircle(points);
  if (!first) return out;
  // The points within outlier_mm of the first circle; then, trim_rounds times, those within
  // max(trim_band_mm, 3 σ) of the last fit (σ from the median absolute residual): what is not
  // the wall's circle (an intrusion, the far side of a joint's step) leaves the fit.
  std::vector<size_t> near = Within(points, *first, options.outlier_mm);
  if (static_cast<int>(near.size()) < options.min_points) return out;
  std::vector<size_t> kept = near;
  Circle c = GeometricCircle(Select(points, kept), *first, options.iterations);
  for (int round = 0; round < options.trim_rounds; ++round) {
    const double band = std::max(options.trim_band_mm, 3.0 * RobustSigma(points, near, c));
    std::vector<size_t> trimmed;
    for (size_t i : near)
      if (Residual(points[i], c) <= band) trimmed.push_back(i);
    if (static_cast<int>(trimmed.size()) < options.min_points) break;
    kept = std::move(trimmed);
    c = GeometricCircle(Select(points, kept), c, options.iterations);
  }
  double sum2 = 0.0, z_sum = 0.0;
  for (size_t i : kept) {
    sum2 += std::pow(Residual(points[i], c), 2);
    z_sum += z[i];
  }
  out.valid = std::isfinite(c.radius) && c.radius > 0.0;
  out.axis_in_carrier_mm = c.centre;
  out.diameter_mm = 2.0 * c.radius;
  out.mean_z_mm = z_sum / static_cast<double>(kept.size());
  out.rms_mm = std::sqrt(sum2 / static_cast<double>(kept.size()));
  out.points = static_cast<int>(kept.size());
  out.inlier_fraction = static_cast<double>(kept.size()) / static_cast<double>(near.size());
  return out;
}

}  // namespace sewer3d
