#pragma once
/// \file
/// The carrier's inclinometer as the robot has it (docs/simulator.md, "Inclinometer"): a
/// three-axis accelerometer at the carrier centre, read as the direction of gravity in the
/// carrier frame. What it measures is the specific force, so the carrier's own acceleration
/// (its speed varying, its lateral wander) tilts the reading; the sensor sits on the carrier
/// a little turned (mounting, one draw per run) and each reading has white noise. Every
/// sample keeps its error terms so the truth can be audited.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sewer3d/sim/trajectory.hpp"

namespace sewer3d {

struct InclinometerOptions {
  bool enabled = true;  ///< false: the run has no inclinometer.csv
  double rate_hz = 20.0;
  double noise_deg = 0.01;    ///< white, per reading and per axis across gravity
  double mounting_deg = 0.1;  ///< the sensor's misalignment on the carrier, per axis (one draw)

  void Check() const;
};

struct InclinometerSample {
  double time_s = 0.0;
  Eigen::Vector3d true_down = Eigen::Vector3d::UnitY();  ///< gravity in the carrier frame
  /// The carrier centre's acceleration (world frame, mm/s²): the reading's error from motion.
  Eigen::Vector3d acceleration_mm_s2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d measured_down = Eigen::Vector3d::UnitY();  ///< what the robot reports (unit)
};

/// Standard gravity, mm/s².
inline constexpr double kGravityMmS2 = 9806.65;

/// Readings every 1/rate_hz s over the trajectory's duration; the world's gravity is +y (the
/// pipe world's "down", sim/pipe_world.hpp).
std::vector<InclinometerSample> SimulateInclinometer(const Trajectory& trajectory,
                                                     const InclinometerOptions& options,
                                                     std::uint64_t seed);

}  // namespace sewer3d
