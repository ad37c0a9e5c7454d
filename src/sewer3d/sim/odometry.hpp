#pragma once
/// \file
/// Cable-length odometry as the robot has it (docs/simulator.md, "Odometry"): the distance
/// travelled since the start, with a scale error (drum diameter), slip of the cable over the
/// drum in given stretches (the count advances by only 1 − fraction of the motion there) and
/// white reading noise. Every sample keeps its error terms so the truth can be audited.

#include <cstdint>
#include <vector>

#include "sewer3d/sim/trajectory.hpp"

namespace sewer3d {

struct OdometrySlip {
  double station_mm = 0.0;  ///< where the stretch starts (pipe station of the carrier centre)
  double length_mm = 0.0;
  double fraction = 0.0;  ///< share of the motion not counted there, 0..1
};

struct OdometryOptions {
  double rate_hz = 20.0;
  double scale_error = 0.004;  ///< measured = (1 + scale_error) · true before slip and noise
  double noise_mm = 0.5;       ///< reading noise, standard deviation
  std::vector<OdometrySlip> slips;

  void Check() const;
};

struct OdometrySample {
  double time_s = 0.0;
  double true_mm = 0.0;   ///< true distance along the pipe since t = 0
  double scale_mm = 0.0;  ///< scale_error · true_mm
  double slip_mm = 0.0;   ///< − Σ fraction · (motion inside each slip stretch so far)
  double noise_mm = 0.0;
  double measured_mm = 0.0;  ///< true + scale + slip + noise: what the robot reports
};

std::vector<OdometrySample> SimulateOdometry(const Trajectory& trajectory,
                                             const OdometryOptions& options, std::uint64_t seed);

/// Σ fraction · |[start, station] ∩ stretch|: the distance the slips have swallowed.
double SlipLossMm(const std::vector<OdometrySlip>& slips, double start_station_mm,
                  double station_mm);

}  // namespace sewer3d
