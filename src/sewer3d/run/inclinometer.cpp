#include "sewer3d/run/inclinometer.hpp"

#include <algorithm>

namespace sewer3d {

std::optional<Eigen::Vector3d> InclinometerDownAt(const std::vector<InclinometerReading>& readings,
                                                  double time_s, double max_gap_s) {
  if (readings.empty() || time_s < readings.front().time_s || time_s > readings.back().time_s)
    return std::nullopt;
  const auto after =
      std::lower_bound(readings.begin(), readings.end(), time_s,
                       [](const InclinometerReading& r, double t) { return r.time_s < t; });
  if (after->time_s == time_s) return after->down_in_carrier.normalized();
  const InclinometerReading& b = *after;
  const InclinometerReading& a = *(after - 1);
  if (b.time_s - a.time_s > max_gap_s) return std::nullopt;
  const double w = (time_s - a.time_s) / (b.time_s - a.time_s);
  const Eigen::Vector3d down = (1.0 - w) * a.down_in_carrier + w * b.down_in_carrier;
  if (!(down.norm() > 0.0)) return std::nullopt;
  return down.normalized();
}

}  // namespace sewer3d
