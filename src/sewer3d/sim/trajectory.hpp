#pragma once
/// \file
/// Robot motion through the pipe world and the capture schedule of a virtual run
/// (docs/simulator.md, "Motion and timing"). All times in seconds from the start of the run.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/run/capture_run.hpp"
#include "sewer3d/sim/pipe_world.hpp"
#include "sewer3d/sim/rig.hpp"

namespace sewer3d {

struct MotionOptions {
  double speed_mm_s = 100.0;
  double speed_variation = 0.05;    ///< ± fraction of the speed, period 2.3 s
  double start_station_mm = 300.0;  ///< carrier centre at t = 0
  double travel_mm = 1000.0;        ///< the run ends when the carrier has travelled this far
  /// Carrier centre's offset from the pipe centreline (x right, y down), mm: robots sit low.
  Eigen::Vector2d offset_mm{0.0, 15.0};
  double wander_mm = 2.0;           ///< slow lateral wander amplitude (periods 3.1 and 4.3 s)
  double roll_deg = 2.0;            ///< mean roll about the carrier axis
  double roll_amplitude_deg = 1.5;  ///< slow roll oscillation, period 5.7 s
  double wobble_deg = 0.3;          ///< pitch and yaw amplitude, periods 0.9 and 1.3 s

  void Check() const;
};

/// The true carrier motion: a smooth function of time from the pipe's path frames.
class Trajectory {
 public:
  Trajectory(const PipeGeometry& pipe, const MotionOptions& options, std::uint64_t seed);
  double StationAt(double t) const;  ///< carrier centre station, mm
  Rigid3d WorldFromCarrier(double t) const;
  double DurationS() const { return duration_s_; }
  const MotionOptions& options() const { return options_; }

 private:
  const PipeGeometry& pipe_;
  MotionOptions options_;
  double phase_[6];
  double duration_s_ = 0.0;
};

struct CaptureOptions {
  double overlap = 0.6;  ///< along the pipe between consecutive acquisitions of a module
  double triplet_interval_ms = 5.0;  ///< texture, pattern, texture this far apart
  /// Odd modules fire this much after even ones, so neighbouring projectors never light the
  /// same wall at once (their fields overlap around the circumference).
  double group_delay_ms = 20.0;
  double exposure_ms = 2.0;
  double nominal_diameter_mm = 300.0;  ///< sets the footprint used for the acquisition rate

  void Check() const;
};

struct CapturePlan {
  double period_s = 0.0;      ///< between acquisitions
  double footprint_mm = 0.0;  ///< measurable length along the pipe per acquisition
  int acquisitions = 0;
  /// Every image to take, ordered by time, with its run file (images/m<k>/…png) and exposure.
  std::vector<RunImage> shots;
};

/// Plans acquisitions every period_s = (1 − overlap) · footprint / speed until the carrier
/// has travelled options.travel_mm.
CapturePlan PlanCaptures(const Rig& rig, const Trajectory& trajectory,
                         const CaptureOptions& options);

}  // namespace sewer3d
