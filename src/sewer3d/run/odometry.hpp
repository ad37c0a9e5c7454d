#pragma once
/// \file
/// The cable counter's readings (odometry.csv, docs/formats.md) and what a run's processing
/// may trust of them. A cable counter only pays out while the robot moves forward, so a
/// reading well below an earlier one is a fault (a glitch, a slipping drum, a reset), not
/// motion: CheckOdometry drops such readings and lists them. Where readings are missing for
/// longer than a bound (dropped, or never recorded), a distance interpolated across the gap is
/// only a guess: OdometryUncertaintyAt says how large. No I/O here: io/ reads the file, the
/// pipeline words the messages.

#include <optional>
#include <vector>

namespace sewer3d {

/// What the robot's cable counter reported: a row of odometry.csv.
struct OdometryReading {
  double time_s = 0.0;
  double distance_mm = 0.0;  ///< cable paid out since the start of the run
  int line = 0;              ///< its line in odometry.csv (0: not read from a file)
};

/// The odometry distance at `time_s`, linear between the two readings around it; nullopt
/// outside the readings' time span or without readings. Readings must be sorted by time.
std::optional<double> OdometryDistanceAt(const std::vector<OdometryReading>& readings,
                                         double time_s);

struct OdometryCheckOptions {
  /// A reading this far below the highest one before it is reading noise and kept; farther
  /// below, the counter went backwards and the reading is dropped (mm, > 0).
  double reversal_tolerance_mm = 2.0;
  /// Longest time between two kept readings across which linear interpolation is trusted
  /// (s, > 0; the counter reports at 20 Hz, every 0.05 s).
  double max_gap_s = 0.2;
  /// In a longer gap the carrier's speed is unknown: its deviation from the gap's mean speed
  /// (σ, mm/s, > 0). An interpolated distance at t in the gap (a, b) then has
  /// σ(t) = speed_sigma · (t − a)(b − t)/(b − a), at most speed_sigma · (b − a)/4 mid-gap.
  double gap_speed_sigma_mm_s = 100.0;
  /// The carrier's mean speed over the kept readings may not exceed this (mm/s, > 0): a
  /// crawler moves well under 1 m/s, so a faster counter is in other units (metres × 1000).
  double max_mean_speed_mm_s = 5000.0;

  /// Throws std::invalid_argument naming the option.
  void Check() const;
};

/// Consecutive readings dropped because the distance went backwards.
struct OdometryReversal {
  int first_line = 0, last_line = 0;  ///< lines in odometry.csv (the readings' `line`)
  int readings = 0;                   ///< dropped
  double before_mm = 0.0;             ///< the highest distance before them
  double lowest_mm = 0.0;             ///< the lowest of them
};

/// A stretch between two kept readings longer than max_gap_s.
struct OdometryGap {
  double from_s = 0.0, to_s = 0.0;  ///< the kept readings around it
  int from_line = 0, to_line = 0;
};

/// What CheckOdometry found wrong with a run's readings.
struct OdometryFindings {
  std::vector<OdometryReversal> reversals;
  std::vector<OdometryGap> gaps;  ///< over the kept readings, sorted by time
  OdometryCheckOptions options;   ///< as checked
};

struct OdometryCheck {
  std::vector<OdometryReading> kept;  ///< the readings to use, sorted by time
  OdometryFindings findings;
};

/// Keeps every reading not below the running maximum of the kept ones by more than
/// reversal_tolerance_mm, groups the dropped ones into reversals, and lists the gaps between
/// kept readings. Readings must be sorted by time (strictly increasing).
OdometryCheck CheckOdometry(const std::vector<OdometryReading>& readings,
                            const OdometryCheckOptions& options = {});

/// How well the kept readings give the distance at `time_s`.
struct OdometryUncertainty {
  double sigma_mm = 0.0;             ///< of the interpolated distance, beyond the reading noise
  double speed_sigma_mm_s = 0.0;     ///< of the carrier's speed there (0 outside gaps)
  const OdometryGap* gap = nullptr;  ///< the gap holding time_s, or null
};

/// 0 outside gaps; inside one, the interpolation's σ (OdometryCheckOptions::gap_speed_sigma_mm_s).
/// The result points into `findings`.
OdometryUncertainty OdometryUncertaintyAt(const OdometryFindings& findings, double time_s);

}  // namespace sewer3d
