#include "sewer3d/run/odometry.hpp"

#include <algorithm>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

std::optional<double> OdometryDistanceAt(const std::vector<OdometryReading>& readings,
                                         double time_s) {
  if (readings.empty() || time_s < readings.front().time_s || time_s > readings.back().time_s)
    return std::nullopt;
  const auto after =
      std::upper_bound(readings.begin(), readings.end(), time_s,
                       [](double t, const OdometryReading& r) { return t < r.time_s; });
  if (after == readings.end()) return readings.back().distance_mm;
  const OdometryReading& b = *after;
  const OdometryReading& a = *(after - 1);
  const double span = b.time_s - a.time_s;
  if (span <= 0.0) return a.distance_mm;
  const double w = (time_s - a.time_s) / span;
  return (1.0 - w) * a.distance_mm + w * b.distance_mm;
}

void OdometryCheckOptions::Check() const {
  ValidatePositive("reversal_tolerance_mm", reversal_tolerance_mm);
  ValidatePositive("max_gap_s", max_gap_s);
  ValidatePositive("gap_speed_sigma_mm_s", gap_speed_sigma_mm_s);
  ValidatePositive("max_mean_speed_mm_s", max_mean_speed_mm_s);
}

OdometryCheck CheckOdometry(const std::vector<OdometryReading>& readings,
                            const OdometryCheckOptions& options) {
  options.Check();
  OdometryCheck out;
  out.findings.options = options;
  double highest = 0.0;  // of the kept readings
  bool in_reversal = false;
  for (size_t i = 0; i < readings.size(); ++i) {
    const OdometryReading& r = readings[i];
    SEWER3D_VALIDATE(i == 0 || r.time_s > readings[i - 1].time_s, "odometry",
                     "readings must be sorted by time, strictly increasing");
    if (out.kept.empty() || r.distance_mm >= highest - options.reversal_tolerance_mm) {
      highest = out.kept.empty() ? r.distance_mm : std::max(highest, r.distance_mm);
      out.kept.push_back(r);
      in_reversal = false;
      continue;
    }
    if (!in_reversal) out.findings.reversals.push_back({r.line, r.line, 0, highest, r.distance_mm});
    OdometryReversal& rev = out.findings.reversals.back();
    rev.last_line = r.line;
    ++rev.readings;
    rev.lowest_mm = std::min(rev.lowest_mm, r.distance_mm);
    in_reversal = true;
  }
  if (out.kept.size() >= 2) {
    const OdometryReading& first = out.kept.front();
    const OdometryReading& last = out.kept.back();
    const double speed = (last.distance_mm - first.distance_mm) / (last.time_s - first.time_s);
    SEWER3D_VALIDATE(speed <= options.max_mean_speed_mm_s, "odometry",
                     "the counter covers " << last.distance_mm - first.distance_mm << " mm in "
                                           << last.time_s - first.time_s << " s (" << speed
                                           << " mm/s; a crawler moves under 1000 mm/s): is "
                                              "distance_mm in millimetres?");
  }
  for (size_t i = 1; i < out.kept.size(); ++i) {
    const OdometryReading& a = out.kept[i - 1];
    const OdometryReading& b = out.kept[i];
    if (b.time_s - a.time_s > options.max_gap_s)
      out.findings.gaps.push_back({a.time_s, b.time_s, a.line, b.line});
  }
  return out;
}

OdometryUncertainty OdometryUncertaintyAt(const OdometryFindings& findings, double time_s) {
  OdometryUncertainty u;
  for (const OdometryGap& g : findings.gaps) {
    if (time_s <= g.from_s || time_s >= g.to_s) continue;
    u.gap = &g;
    u.speed_sigma_mm_s = findings.options.gap_speed_sigma_mm_s;
    u.sigma_mm = u.speed_sigma_mm_s * (time_s - g.from_s) * (g.to_s - time_s) / (g.to_s - g.from_s);
    break;
  }
  return u;
}

}  // namespace sewer3d
