#include "sewer3d/sim/inclinometer.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/material.hpp"

namespace sewer3d {
namespace {

// A small rotation about the two axes across `down` with the given angles (rad).
Eigen::Quaterniond TiltAcross(const Eigen::Vector3d& down, double angle_a, double angle_b) {
  const Eigen::Vector3d a = down.unitOrthogonal(), b = down.cross(a);
  const Eigen::Vector3d turn = angle_a * a + angle_b * b;
  const double angle = turn.norm();
  if (angle == 0.0) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, turn / angle));
}

// The carrier centre's acceleration by central differences (one-sided at the run's ends).
Eigen::Vector3d Acceleration(const Trajectory& trajectory, double t) {
  constexpr double h = 0.01;
  const double mid = std::clamp(t, h, std::max(h, trajectory.DurationS() - h));
  const auto at = [&](double s) { return trajectory.WorldFromCarrier(s).translation; };
  return (at(mid + h) - 2.0 * at(mid) + at(mid - h)) / (h * h);
}

}  // namespace

void InclinometerOptions::Check() const {
  SEWER3D_VALIDATE(rate_hz >= 1.0 && rate_hz <= 1000.0, "rate_hz",
                   "must be 1..1000, got " << rate_hz);
  // An inclinometer worth carrying reads to a tenth of a degree or better.
  SEWER3D_VALIDATE(noise_deg >= 0.0 && noise_deg <= 1.0, "noise_deg",
                   "must be 0..1°, got " << noise_deg);
  SEWER3D_VALIDATE(mounting_deg >= 0.0 && mounting_deg <= 5.0, "mounting_deg",
                   "must be 0..5°, got " << mounting_deg);
}

std::vector<InclinometerSample> SimulateInclinometer(const Trajectory& trajectory,
                                                     const InclinometerOptions& o,
                                                     std::uint64_t seed) {
  o.Check();
  std::vector<InclinometerSample> out;
  if (!o.enabled) return out;
  const Eigen::Vector3d gravity(0.0, kGravityMmS2, 0.0);
  const Eigen::Quaterniond mounting =
      TiltAcross(Eigen::Vector3d::UnitY(), DegToRad(o.mounting_deg) * HashNormal(seed, 0x1c0, 0),
                 DegToRad(o.mounting_deg) * HashNormal(seed, 0x1c0, 1));
  const int n = static_cast<int>(std::floor(trajectory.DurationS() * o.rate_hz)) + 1;
  for (int i = 0; i < n; ++i) {
    InclinometerSample s;
    s.time_s = i / o.rate_hz;
    const Eigen::Quaterniond carrier_from_world =
        trajectory.WorldFromCarrier(s.time_s).rotation.conjugate();
    s.true_down = carrier_from_world * Eigen::Vector3d::UnitY();
    s.acceleration_mm_s2 = Acceleration(trajectory, s.time_s);
    // The accelerometer feels −(a − g): gravity less the carrier's own acceleration.
    const Eigen::Vector3d felt = mounting * (carrier_from_world * (gravity - s.acceleration_mm_s2));
    const Eigen::Vector3d down = felt.normalized();
    s.measured_down = TiltAcross(down, DegToRad(o.noise_deg) * HashNormal(seed, 0x1c1, 2 * i),
                                 DegToRad(o.noise_deg) * HashNormal(seed, 0x1c1, 2 * i + 1)) *
                      down;
    out.push_back(s);
  }
  return out;
}

}  // namespace sewer3d
