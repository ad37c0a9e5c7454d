#pragma once
/// \file
/// The carrier's inclinometer (inclinometer.csv, docs/formats.md): the direction of gravity in
/// the carrier frame, as a three-axis accelerometer at rest reads it (the specific force
/// reversed and normalised). Sewer crawlers carry one to measure a pipe's gradient; here it
/// also tells the registration which way is down at every acquisition, which no relative
/// registration can (a turn every step shares bends the model, docs/registration.md). Optional:
/// a run without it is registered without it. No I/O here (io/inclinometer_io.hpp).

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace sewer3d {

/// One row of inclinometer.csv.
struct InclinometerReading {
  double time_s = 0.0;
  Eigen::Vector3d down_in_carrier = Eigen::Vector3d::UnitY();  ///< unit
  int line = 0;  ///< its line in inclinometer.csv (0: not read from a file)
};

/// Gravity's direction in the carrier frame at `time_s`: linear between the two readings around
/// it, normalised. nullopt without readings, outside their time span, or where the two are more
/// than `max_gap_s` apart (the carrier may have turned in between). Readings sorted by time.
std::optional<Eigen::Vector3d> InclinometerDownAt(const std::vector<InclinometerReading>& readings,
                                                  double time_s, double max_gap_s = 0.5);

}  // namespace sewer3d
