#include "sewer3d/sim/trajectory.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/material.hpp"

namespace sewer3d {
namespace {

constexpr double kSpeedPeriodS = 2.3;

}  // namespace

void MotionOptions::Check() const {
  // A crawler between 1 mm/s (100 m in a day) and 1 m/s.
  SEWER3D_VALIDATE(speed_mm_s >= 1.0 && speed_mm_s <= 1000.0, "speed_mm_s",
                   "a crawler's speed must be 1..1000 mm/s, got " << speed_mm_s);
  SEWER3D_VALIDATE(speed_variation >= 0.0 && speed_variation < 0.5, "speed_variation",
                   "must be >= 0 and < 0.5, got " << speed_variation);
  ValidatePositive("travel_mm", travel_mm);
  SEWER3D_VALIDATE(offset_mm.allFinite(), "offset_mm", "must be finite");
  ValidateNotNegative("wander_mm", wander_mm);
  SEWER3D_VALIDATE(std::abs(roll_deg) <= 180.0, "roll_deg",
                   "must be within ±180, got " << roll_deg);
  ValidateNotNegative("roll_amplitude_deg", roll_amplitude_deg);
  SEWER3D_VALIDATE(wobble_deg >= 0.0 && wobble_deg < 10.0, "wobble_deg",
                   "must be >= 0 and < 10, got " << wobble_deg);
}

Trajectory::Trajectory(const PipeGeometry& pipe, const MotionOptions& options, std::uint64_t seed)
    : pipe_(pipe), options_(options) {
  options_.Check();
  for (int i = 0; i < 6; ++i) phase_[i] = kTwoPi * HashUniform(seed, 0x7a, i);
  // Duration: first time the carrier has travelled travel_mm (station is increasing).
  double lo = 0.0, hi = 2.0 * options_.travel_mm / options_.speed_mm_s;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (StationAt(mid) - options_.start_station_mm < options_.travel_mm ? lo : hi) = mid;
  }
  duration_s_ = hi;
}

double Trajectory::StationAt(double t) const {
  const MotionOptions& o = options_;
  const double a = o.speed_variation * o.speed_mm_s * kSpeedPeriodS / kTwoPi;
  return o.start_station_mm + o.speed_mm_s * t +
         a * (std::sin(kTwoPi * t / kSpeedPeriodS + phase_[0]) - std::sin(phase_[0]));
}

Rigid3d Trajectory::WorldFromCarrier(double t) const {
  const MotionOptions& o = options_;
  const Eigen::Vector3d offset(
      o.offset_mm.x() + o.wander_mm * std::sin(kTwoPi * t / 3.1 + phase_[1]),
      o.offset_mm.y() + o.wander_mm * std::sin(kTwoPi * t / 4.3 + phase_[2]), 0.0);
  const double roll =
      DegToRad(o.roll_deg + o.roll_amplitude_deg * std::sin(kTwoPi * t / 5.7 + phase_[3]));
  const double pitch = DegToRad(o.wobble_deg * std::sin(kTwoPi * t / 0.9 + phase_[4]));
  const double yaw = DegToRad(o.wobble_deg * std::sin(kTwoPi * t / 1.3 + phase_[5]));
  const Eigen::Quaterniond attitude = Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()) *
                                      Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
                                      Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY());
  return pipe_.PathFrame(StationAt(t)) * Rigid3d(attitude, offset);
}

void CaptureOptions::Check() const {
  SEWER3D_VALIDATE(overlap >= 0.0 && overlap < 0.95, "overlap",
                   "must be >= 0 and < 0.95, got " << overlap);
  ValidatePositive("triplet_interval_ms", triplet_interval_ms);
  ValidateNotNegative("group_delay_ms", group_delay_ms);
  // 10 µs at least, as acquisitions.csv requires (io/run_io.cpp).
  SEWER3D_VALIDATE(exposure_ms >= 0.01 && exposure_ms < triplet_interval_ms, "exposure_ms",
                   "must be at least 0.01 ms and shorter than triplet_interval_ms ("
                       << triplet_interval_ms << "), got " << exposure_ms);
  ValidatePositive("nominal_diameter_mm", nominal_diameter_mm);
}

CapturePlan PlanCaptures(const Rig& rig, const Trajectory& trajectory, const CaptureOptions& o) {
  o.Check();
  CapturePlan plan;
  // The shortest measurable footprint among the modules sets the rate.
  plan.footprint_mm = 1e9;
  for (size_t k = 0; k < rig.modules.size(); ++k) {
    const WallCoverage c = ModuleCoverage(rig, static_cast<int>(k), o.nominal_diameter_mm,
                                          Eigen::Vector2d::Zero(), true, 16);
    SEWER3D_VALIDATE(c.any, "nominal_diameter_mm",
                     "module " << rig.modules[k].name << " measures nothing of a Ø"
                               << o.nominal_diameter_mm << " pipe");
    plan.footprint_mm = std::min(plan.footprint_mm, c.station_to_mm - c.station_from_mm);
  }
  plan.period_s = (1.0 - o.overlap) * plan.footprint_mm / trajectory.options().speed_mm_s;
  // A module's triplet (and the odd modules' delay) must end before its next acquisition.
  const double triplet_s = (2.0 * o.triplet_interval_ms + o.group_delay_ms + o.exposure_ms) * 1e-3;
  // The field named is the larger share of the triplet's time.
  SEWER3D_VALIDATE(
      triplet_s < plan.period_s,
      2.0 * o.triplet_interval_ms >= o.group_delay_ms ? "triplet_interval_ms" : "group_delay_ms",
      "a triplet takes " << triplet_s * 1e3 << " ms (two intervals, the group delay "
                         << "and an exposure), but acquisitions follow every "
                         << plan.period_s * 1e3
                         << " ms at this speed and overlap: the triplets would "
                            "interleave");
  const double last_start = trajectory.DurationS();
  for (int j = 0; j * plan.period_s <= last_start; ++j) {
    for (size_t k = 0; k < rig.modules.size(); ++k) {
      const double t0 = j * plan.period_s + (k % 2) * o.group_delay_ms * 1e-3;
      for (int i = 0; i < 3; ++i) {
        const auto kind = static_cast<ImageKind>(i);
        plan.shots.push_back({static_cast<int>(k), j, kind, t0 + i * o.triplet_interval_ms * 1e-3,
                              o.exposure_ms,
                              "images/" + ImageStem(static_cast<int>(k), j, kind) + ".png"});
      }
    }
    plan.acquisitions = j + 1;
  }
  std::stable_sort(plan.shots.begin(), plan.shots.end(),
                   [](const RunImage& a, const RunImage& b) { return a.time_s < b.time_s; });
  return plan;
}

}  // namespace sewer3d
