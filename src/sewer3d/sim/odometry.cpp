#include "sewer3d/sim/odometry.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sewer3d/core/check.hpp"
#include "sewer3d/sim/material.hpp"

namespace sewer3d {

void OdometryOptions::Check() const {
  // A cable counter reports at least once a second (the pipeline interpolates between).
  SEWER3D_VALIDATE(rate_hz >= 1.0 && rate_hz <= 1000.0, "rate_hz",
                   "must be 1..1000, got " << rate_hz);
  SEWER3D_VALIDATE(std::abs(scale_error) < 0.2, "scale_error",
                   "must be within ±0.2, got " << scale_error);
  // A cable counter reads to a millimetre or two; 50 mm of noise per reading is no counter.
  SEWER3D_VALIDATE(noise_mm >= 0.0 && noise_mm <= 50.0, "noise_mm",
                   "must be 0..50 mm, got " << noise_mm);
  for (size_t i = 0; i < slips.size(); ++i) {
    const std::string field = "slips[" + std::to_string(i) + "].";
    ValidateNotNegative(field + "length_mm", slips[i].length_mm);
    SEWER3D_VALIDATE(slips[i].fraction >= 0.0 && slips[i].fraction <= 1.0, field + "fraction",
                     "must be 0..1, got " << slips[i].fraction);
  }
  // Where stretches overlap their fractions add up; more than all of the motion lost would run
  // the counter backwards. The sum is largest at some stretch's start.
  for (size_t i = 0; i < slips.size(); ++i) {
    const double at = slips[i].station_mm;
    double sum = 0.0;
    for (const OdometrySlip& s : slips) {
      if (s.station_mm <= at && at < s.station_mm + s.length_mm) sum += s.fraction;
    }
    SEWER3D_VALIDATE(sum <= 1.0 + 1e-9, "slips[" + std::to_string(i) + "].station_mm",
                     "overlapping slips lose fractions summing to "
                         << sum << " of the motion at " << at
                         << " mm, more than all of it: the counter would run backwards");
  }
}

double SlipLossMm(const std::vector<OdometrySlip>& slips, double start, double station) {
  double loss = 0.0;
  for (const OdometrySlip& s : slips) {
    const double a = std::max(start, s.station_mm),
                 b = std::min(station, s.station_mm + s.length_mm);
    if (b > a) loss += s.fraction * (b - a);
  }
  return loss;
}

std::vector<OdometrySample> SimulateOdometry(const Trajectory& trajectory, const OdometryOptions& o,
                                             std::uint64_t seed) {
  o.Check();
  std::vector<OdometrySample> out;
  const double start = trajectory.StationAt(0.0);
  const int n = static_cast<int>(std::floor(trajectory.DurationS() * o.rate_hz)) + 1;
  for (int i = 0; i < n; ++i) {
    OdometrySample s;
    s.time_s = i / o.rate_hz;
    const double station = trajectory.StationAt(s.time_s);
    s.true_mm = station - start;
    s.scale_mm = o.scale_error * s.true_mm;
    s.slip_mm = -SlipLossMm(o.slips, start, station);
    s.noise_mm = o.noise_mm * HashNormal(seed, 0x0d0, i);
    s.measured_mm = s.true_mm + s.scale_mm + s.slip_mm + s.noise_mm;
    out.push_back(s);
  }
  return out;
}

}  // namespace sewer3d
