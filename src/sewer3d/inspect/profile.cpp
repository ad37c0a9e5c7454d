#include "sewer3d/inspect/profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

void ProfileOptions::Check() const {
  ValidatePositive("step_mm", step_mm);
  ValidateNotNegative("band_mm", band_mm);
  SEWER3D_VALIDATE(min_coverage > 0.0 && min_coverage <= 1.0, "min_coverage",
                   "must be in (0, 1], got " << min_coverage);
  SEWER3D_VALIDATE(max_gap_deg >= 0.0 && max_gap_deg < 180.0, "max_gap_deg",
                   "must be in [0, 180), got " << max_gap_deg);
  SEWER3D_VALIDATE(ring_step_deg > 0.0 && ring_step_deg <= 45.0, "ring_step_deg",
                   "must be in (0, 45], got " << ring_step_deg);
  SEWER3D_VALIDATE(axis_half_width_deg >= 0.0 && axis_half_width_deg <= 45.0, "axis_half_width_deg",
                   "must be in [0, 45], got " << axis_half_width_deg);
  ValidateNotNegative("nominal_diameter_mm", nominal_diameter_mm);
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = std::numbers::pi;

/// The mean of the diameters whose direction (mod π) lies within `half_width` of `axis` (rad);
/// the nearest one when none does.
double DiameterAlong(const std::vector<double>& diameter, const std::vector<double>& direction,
                     double axis, double half_width) {
  double sum = 0.0, nearest = kPi;
  int count = 0;
  size_t nearest_index = 0;
  for (size_t s = 0; s < diameter.size(); ++s) {
    double d = std::fmod(std::abs(direction[s] - axis), kPi);
    d = std::min(d, kPi - d);
    if (d <= half_width) sum += diameter[s], ++count;
    if (d < nearest) nearest = d, nearest_index = s;
  }
  return count > 0 ? sum / count : diameter[nearest_index];
}

void SetUnmeasured(ProfileRow& row) {
  for (double* field : {&row.height_mm, &row.width_mm, &row.circumference_mm, &row.mean_diameter_mm,
                        &row.min_diameter_mm, &row.max_diameter_mm, &row.vertical_change_pct,
                        &row.horizontal_change_pct, &row.ovality_en_pct, &row.ovality_astm_pct,
                        &row.min_radius_mm, &row.mean_radius_mm, &row.max_radius_mm})
    *field = kNaN;
}

/// The widest circular run of false in `has` (cells); has.size() when none is true.
int WidestGap(const std::vector<bool>& has) {
  const int n = static_cast<int>(has.size());
  const auto first = std::find(has.begin(), has.end(), true);
  if (first == has.end()) return n;
  const int start = static_cast<int>(first - has.begin());
  int widest = 0, run = 0;
  for (int i = 1; i <= n; ++i) {
    if (has[(start + i) % n]) {
      widest = std::max(widest, run);
      run = 0;
    } else {
      ++run;
    }
  }
  return widest;
}

/// Fills the cells without data by linear interpolation around the ring between the nearest
/// cells with data on either side (at least one cell has data).
void BridgeGaps(std::vector<double>& r, const std::vector<bool>& has) {
  const int n = static_cast<int>(r.size());
  const int start = static_cast<int>(std::find(has.begin(), has.end(), true) - has.begin());
  int last = start;
  for (int i = 1; i <= n; ++i) {
    const int k = (start + i) % n;
    if (!has[k]) continue;
    const int gap = (k - last + n) % n - 1;  // cells between last and k (k == last: the rest)
    const int span = gap > 0 ? gap + 1 : (k == last ? n : 0);
    for (int j = 1; j < span; ++j) {
      const double t = static_cast<double>(j) / span;
      r[(last + j) % n] = (1.0 - t) * r[last] + t * r[k];
    }
    last = k;
  }
}

}  // namespace

ProfileRow MeasureRing(std::span<const double> radius_mm, double nominal_diameter_mm,
                       const ProfileOptions& options) {
  const int n = static_cast<int>(radius_mm.size());
  SEWER3D_CHECK(n >= 8, "a ring needs at least 8 radii, got " << n);
  ValidatePositive("nominal_diameter_mm", nominal_diameter_mm);
  // An even number of sectors, no more than the radii, so each holds at least one radius.
  int m = 2 * std::max(4, static_cast<int>(std::lround(180.0 / options.ring_step_deg)));
  m = std::min(m, n - n % 2);
  std::vector<double> r(m, 0.0), angle(m, 0.0);
  std::vector<int> count(m, 0);
  for (int k = 0; k < n; ++k) {
    const int s = std::min(m - 1, static_cast<int>((k + 0.5) * m / n));
    r[s] += radius_mm[k];
    angle[s] += (k + 0.5) * 2.0 * kPi / n;
    ++count[s];
  }
  ProfileRow row;
  double perimeter = 0.0, radius_sum = 0.0;
  row.min_radius_mm = std::numeric_limits<double>::infinity();
  row.max_radius_mm = -row.min_radius_mm;
  for (int s = 0; s < m; ++s) {
    r[s] /= count[s];
    angle[s] /= count[s];
    radius_sum += r[s];
    row.min_radius_mm = std::min(row.min_radius_mm, r[s]);
    row.max_radius_mm = std::max(row.max_radius_mm, r[s]);
  }
  for (int s = 0; s < m; ++s) {
    const int t = (s + 1) % m;
    perimeter += std::hypot(r[t] * std::cos(angle[t]) - r[s] * std::cos(angle[s]),
                            r[t] * std::sin(angle[t]) - r[s] * std::sin(angle[s]));
  }
  // Diameters: each sector of the first half with the one opposite.
  std::vector<double> diameter(m / 2), direction(m / 2);
  for (int s = 0; s < m / 2; ++s) {
    diameter[s] = r[s] + r[s + m / 2];
    direction[s] = angle[s];
  }
  const auto [lo, hi] = std::minmax_element(diameter.begin(), diameter.end());
  const double half_width = options.axis_half_width_deg * kPi / 180.0;
  row.mean_radius_mm = radius_sum / m;
  row.circumference_mm = perimeter;
  row.mean_diameter_mm = perimeter / kPi;
  row.min_diameter_mm = *lo;
  row.max_diameter_mm = *hi;
  row.height_mm = DiameterAlong(diameter, direction, 0.0, half_width);
  row.width_mm = DiameterAlong(diameter, direction, 0.5 * kPi, half_width);
  row.vertical_change_pct = 100.0 * (row.height_mm - nominal_diameter_mm) / nominal_diameter_mm;
  row.horizontal_change_pct = 100.0 * (row.width_mm - nominal_diameter_mm) / nominal_diameter_mm;
  row.ovality_en_pct = 100.0 * (*hi - *lo) / (*hi + *lo);
  row.ovality_astm_pct = 100.0 * (*hi - row.mean_diameter_mm) / row.mean_diameter_mm;
  return row;
}

Profile ComputeProfile(const PipeMaps& maps, double radius_mm, const ProfileOptions& options) {
  options.Check();
  ValidatePositive("radius_mm", radius_mm);
  const MapGrid& g = maps.grid;
  SEWER3D_CHECK(maps.displacement_mm.rows == g.rows && maps.displacement_mm.cols == g.cols &&
                maps.coverage.rows == g.rows && maps.coverage.cols == g.cols);
  Profile profile;
  profile.nominal_diameter_mm =
      options.nominal_diameter_mm > 0.0 ? options.nominal_diameter_mm : 2.0 * radius_mm;
  if (g.rows == 0 || g.cols < 8) return profile;
  const double end_mm = g.station0_mm + g.rows * g.resolution_mm;
  std::vector<double> sum(g.cols), r(g.cols);
  std::vector<int> count(g.cols);
  std::vector<bool> has(g.cols);
  for (auto k = static_cast<long>(std::ceil(g.station0_mm / options.step_mm));; ++k) {
    const double station = static_cast<double>(k) * options.step_mm;
    if (station >= end_mm) break;
    if (station < g.station0_mm) continue;
    // Rows whose centre lies within the band; at least the row holding the station.
    const auto row_of = [&](double s) { return (s - g.station0_mm) / g.resolution_mm - 0.5; };
    int r0 = static_cast<int>(std::ceil(row_of(station - 0.5 * options.band_mm)));
    int r1 = static_cast<int>(std::floor(row_of(station + 0.5 * options.band_mm)));
    if (r1 < r0) r0 = r1 = static_cast<int>(std::floor(row_of(station) + 0.5));
    r0 = std::clamp(r0, 0, g.rows - 1);
    r1 = std::clamp(r1, 0, g.rows - 1);
    std::fill(sum.begin(), sum.end(), 0.0);
    std::fill(count.begin(), count.end(), 0);
    for (int row = r0; row <= r1; ++row) {
      const float* d = maps.displacement_mm[row];
      const unsigned char* c = maps.coverage[row];
      for (int col = 0; col < g.cols; ++col) {
        if (c[col] == 0 || !std::isfinite(d[col])) continue;
        sum[col] += d[col];
        ++count[col];
      }
    }
    int measured = 0;
    for (int col = 0; col < g.cols; ++col) {
      has[col] = count[col] > 0;
      r[col] = has[col] ? radius_mm + sum[col] / count[col] : kNaN;
      measured += has[col] ? 1 : 0;
    }
    const double coverage = static_cast<double>(measured) / g.cols;
    const double widest_gap_deg = 360.0 * WidestGap(has) / g.cols;
    ProfileRow row;
    if (coverage >= options.min_coverage && widest_gap_deg <= options.max_gap_deg) {
      BridgeGaps(r, has);
      row = MeasureRing(r, profile.nominal_diameter_mm, options);
    } else {
      SetUnmeasured(row);
    }
    row.station_mm = station;
    row.coverage = coverage;
    row.widest_gap_deg = widest_gap_deg;
    profile.rows.push_back(row);
  }
  return profile;
}

}  // namespace sewer3d
