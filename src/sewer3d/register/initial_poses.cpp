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
  SEWER3D_VALIDATE(min_points >= 8, "min_points", "must be >= 8, got " << min_points);
  SEWER3D_VALIDATE(min_modules >= 1, "min_modules", "must be >= 1, got " << min_modules);
  ValidatePositive("outlier_mm", outlier_mm);
  circle.Check();
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
  // What is not the wall's circle (an intrusion, the far side of a joint's step) gets no
  // weight; the inlier share is taken of the points near the circle, so a view into a
  // connection's bore does not count against it, a joint's far side does.
  std::vector<std::uint8_t> inlier;
  const CircleFit fit = FitCircleRobust(points, options.circle, &inlier);
  if (!fit.converged) return out;
  int near = 0, kept = 0;
  double z_sum = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    near += std::abs((points[i] - fit.centre).norm() - fit.radius_mm) <= options.outlier_mm;
    if (!inlier[i]) continue;
    ++kept;
    z_sum += z[i];
  }
  if (kept < options.min_points) return out;
  out.valid = true;
  out.axis_in_carrier_mm = fit.centre;
  out.diameter_mm = 2.0 * fit.radius_mm;
  out.mean_z_mm = z_sum / kept;
  out.rms_mm = fit.rms_mm;
  out.points = kept;
  out.inlier_fraction = static_cast<double>(kept) / std::max(kept, near);
  return out;
}

}  // namespace sewer3d
