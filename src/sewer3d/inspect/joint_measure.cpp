#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "sewer3d/core/units.hpp"
#include "sewer3d/inspect/joints.hpp"
#include "sewer3d/inspect/robust_stats.hpp"
#include "sewer3d/model/unroll.hpp"

namespace sewer3d {
namespace {

/// Least-squares line d = value + slope · x through the column's finite values at x.
struct SideLine {
  double value = 0.0;
  double slope = 0.0;
  double rms = 0.0;  ///< of the values about the line
  bool ok = false;
};

SideLine FitSide(const cv::Mat1f& d, int col, int row_begin, int row_end,
                 const std::vector<double>& x_of_row) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int r = std::max(0, row_begin); r < std::min(d.rows, row_end); ++r) {
    const float v = d(r, col);
    if (!std::isfinite(v)) continue;
    const double x = x_of_row[r];
    n += 1;
    sx += x;
    sy += v;
    sxx += x * x;
    sxy += x * v;
  }
  SideLine line;
  const double det = n * sxx - sx * sx;
  if (2 * n < row_end - row_begin || n < 4 || det <= 0.0) return line;
  line.slope = (n * sxy - sx * sy) / det;
  line.value = (sy - line.slope * sx) / n;
  double sum2 = 0.0;
  for (int r = std::max(0, row_begin); r < std::min(d.rows, row_end); ++r) {
    const float v = d(r, col);
    if (std::isfinite(v)) sum2 += std::pow(v - line.value - line.slope * x_of_row[r], 2);
  }
  line.rms = std::sqrt(sum2 / n);
  line.ok = true;
  return line;
}

struct Sides {
  std::vector<int> cols;
  std::vector<SideLine> before, after;
};

/// `sides` without the columns where either side's wall is no straight line (a connection, a
/// deposit or a spall in the side's rows): line RMS over `factor` times the median of all
/// sides' RMS.
Sides WithoutCrookedColumns(const Sides& sides, double factor) {
  std::vector<double> rms;
  for (std::size_t i = 0; i < sides.cols.size(); ++i) {
    rms.push_back(sides.before[i].rms);
    rms.push_back(sides.after[i].rms);
  }
  if (rms.empty()) return sides;
  const double limit = factor * Median(rms);
  Sides kept;
  for (std::size_t i = 0; i < sides.cols.size(); ++i) {
    if (std::max(sides.before[i].rms, sides.after[i].rms) > limit) continue;
    kept.cols.push_back(sides.cols[i]);
    kept.before.push_back(sides.before[i]);
    kept.after.push_back(sides.after[i]);
  }
  return kept;
}

/// The two side lines of every column measured on both sides of a gap `gap_mm` wide.
Sides FitSides(const CoarseMap& map, double station_mm, double gap_mm, const JointOptions& o,
               const std::vector<double>& x) {
  const double row_mm = map.RowMm(), s0 = map.fine.station0_mm;
  auto row_at = [&](double s) { return static_cast<int>(std::floor((s - s0) / row_mm)); };
  const double inner = 0.5 * gap_mm + o.side_margin_mm;
  Sides sides;
  for (int c = 0; c < map.displacement_mm.cols; ++c) {
    const SideLine before =
        FitSide(map.displacement_mm, c, row_at(station_mm - inner - o.side_length_mm) + 1,
                row_at(station_mm - inner), x);
    const SideLine after = FitSide(map.displacement_mm, c, row_at(station_mm + inner) + 1,
                                   row_at(station_mm + inner + o.side_length_mm), x);
    if (!before.ok || !after.ok) continue;
    sides.cols.push_back(c);
    sides.before.push_back(before);
    sides.after.push_back(after);
  }
  return WithoutCrookedColumns(sides, o.max_side_rms_factor);
}

struct GapMeasure {
  double gap_mm = 0.0;      ///< median over columns of the open length between the side lines
  double depth_mm = 0.0;    ///< of its bottom where seen (0 where not)
  double centre_mm = 0.0;   ///< median over columns of the open length's centroid (x)
  double open_share = 0.0;  ///< share of the columns with any open length
};

/// The gap at the pipe's axis from its widths around the turn: a joint deflected by α opens
/// by R tan α on one side and closes by as much on the other (the next pipe's end face turns
/// with it), so the widths are the gap plus a first harmonic; their median would lean toward
/// the wider side wherever the narrow side's columns are bridged or left out. The mean term
/// of a robust first-harmonic fit; the median where too few columns are open for one.
double GapAtTheAxis(const std::vector<double>& theta, const std::vector<double>& widths) {
  const Eigen::VectorXd k = RobustHarmonicFit(theta, widths, 1);
  return k.size() == 3 ? std::max(0.0, k(0)) : Median(widths);
}

/// A column's open length over rows [r0, r1): missing cells count as open, and measured ones
/// by their depth below the wall of their side as a share of the gap's bottom there. The
/// bottom is the column's cells deeper than both side lines by more than min_gap_depth_mm,
/// at their lower quartile (so that its noisy cells count as wholly open, and a cell half
/// wall, half bottom at a 1 mm edge as half); each side's share is taken against that side's
/// own line, since past an offset the bottom lies less deep below the next pipe's wall than
/// below this one's. Where the column has no such bottom only missing cells are open.
/// Returns {open length in rows, centroid of the open rows (x, weighted)}.
std::pair<double, double> OpenRows(const CoarseMap& map, int col, const SideLine& before,
                                   const SideLine& after, int r0, int r1, const JointOptions& o,
                                   const std::vector<double>& x) {
  const auto depth = [&](const SideLine& line, int r) {
    return map.displacement_mm(r, col) - (line.value + line.slope * x[r]);
  };
  std::vector<double> bottom;
  for (int r = r0; r < r1; ++r) {
    if (std::isfinite(map.displacement_mm(r, col)) &&
        std::min(depth(before, r), depth(after, r)) > o.min_gap_depth_mm)
      bottom.push_back(map.displacement_mm(r, col));
  }
  const double level =
      bottom.empty() ? std::numeric_limits<double>::quiet_NaN() : Percentile(bottom, 0.25);
  double open = 0.0, moment = 0.0;
  for (int r = r0; r < r1; ++r) {
    const float v = map.displacement_mm(r, col), frac = map.measured(r, col);
    const SideLine& line = x[r] < 0.0 ? before : after;
    const double reach = level - (line.value + line.slope * x[r]);  // NaN without a bottom
    const double deep = std::isfinite(v) && reach > o.min_gap_depth_mm
                            ? std::clamp(depth(line, r) / reach, 0.0, 1.0)
                            : 0.0;
    const double here = (1.0 - frac) + frac * deep;
    open += here;
    moment += here * x[r];
  }
  return {open, open > 0.0 ? moment / open : 0.0};
}

GapMeasure MeasureGap(const CoarseMap& map, const Sides& sides, double station_mm,
                      double half_window_mm, const JointOptions& o, const std::vector<double>& x) {
  if (sides.cols.empty()) return {};
  const double row_mm = map.RowMm(), s0 = map.fine.station0_mm;
  const int r0 =
      std::max(0, static_cast<int>(std::floor((station_mm - half_window_mm - s0) / row_mm)));
  const int r1 = std::min(map.displacement_mm.rows,
                          static_cast<int>(std::ceil((station_mm + half_window_mm - s0) / row_mm)));
  std::vector<double> deepest;
  for (std::size_t i = 0; i < sides.cols.size(); ++i) {
    double most = 0.0;
    for (int r = r0; r < r1; ++r) {
      const float v = map.displacement_mm(r, sides.cols[i]);
      const SideLine& line = x[r] < 0.0 ? sides.before[i] : sides.after[i];
      if (std::isfinite(v)) most = std::max(most, v - (line.value + line.slope * x[r]));
    }
    deepest.push_back(most);
  }
  const double bottom = Median(deepest);
  const bool seen = bottom >= 4.0 * o.min_gap_depth_mm;
  std::vector<double> widths, centres;
  for (std::size_t i = 0; i < sides.cols.size(); ++i) {
    const auto [open, centre] =
        OpenRows(map, sides.cols[i], sides.before[i], sides.after[i], r0, r1, o, x);
    widths.push_back(open * row_mm);
    if (open > 0.0) centres.push_back(centre);
  }
  std::vector<double> open_widths, open_theta;
  for (std::size_t i = 0; i < widths.size(); ++i) {
    if (widths[i] <= 0.0) continue;
    open_widths.push_back(widths[i]);
    open_theta.push_back(map.ColClockRad(sides.cols[i]));
  }
  const bool most_open = static_cast<double>(open_widths.size()) >=
                             o.min_open_share * static_cast<double>(widths.size()) &&
                         !open_widths.empty();
  // Where few columns are open, the median over all of them (mostly 0: not in the data).
  return {most_open ? GapAtTheAxis(open_theta, open_widths) : Median(widths), seen ? bottom : 0.0,
          centres.empty() ? 0.0 : Median(centres),
          static_cast<double>(open_widths.size()) / static_cast<double>(widths.size())};
}

}  // namespace

JointMeasure MeasureJoint(const CoarseMap& map, const Centreline& centreline, double station_mm,
                          double gap_guess_mm, const JointOptions& o) {
  const cv::Mat1f& d = map.displacement_mm;
  const double row_mm = map.RowMm(), s0 = map.fine.station0_mm;
  std::vector<double> x(d.rows);
  for (int r = 0; r < d.rows; ++r) x[r] = s0 + (r + 0.5) * row_mm - station_mm;
  JointMeasure m;
  m.station_mm = station_mm;
  // The gap measured between sides left clear of the guess (a joint found by its step:
  // of the band a gap may hide in, and only where enough columns show it open); then the
  // joint moved to its centre, and the sides fitted again clear of the measured gap.
  const double guess = gap_guess_mm > 0.0 ? gap_guess_mm + 2.0 * o.gap_reach_mm : o.unseen_gap_mm;
  const Sides first = FitSides(map, station_mm, guess + 2.0 * row_mm, o, x);
  const GapMeasure g = MeasureGap(map, first, station_mm, 0.5 * guess + 2.0 * row_mm, o, x);
  if (gap_guess_mm > 0.0 || (g.open_share >= o.min_open_share && g.gap_mm > 0.0)) {
    m.gap_mm = g.gap_mm;
    m.gap_depth_mm = g.depth_mm;
    m.station_mm = station_mm += g.centre_mm;
    for (double& xr : x) xr -= g.centre_mm;
  }
  const double cleared = std::max(m.gap_mm, o.unseen_gap_mm);
  const Sides sides = FitSides(map, station_mm, cleared, o, x);
  std::vector<double> theta, step, bend;
  for (std::size_t i = 0; i < sides.cols.size(); ++i) {
    theta.push_back(map.ColClockRad(sides.cols[i]));
    step.push_back(sides.after[i].value - sides.before[i].value);
    bend.push_back(sides.after[i].slope - sides.before[i].slope);
  }
  const double inner = 0.5 * cleared + o.side_margin_mm;
  m.row_begin = std::max(0, static_cast<int>(std::floor((station_mm - inner - s0) / row_mm)));
  m.row_end = std::min(d.rows, static_cast<int>(std::ceil((station_mm + inner - s0) / row_mm)));
  m.side_coverage = static_cast<double>(theta.size()) / d.cols;
  const Eigen::VectorXd k_step = RobustHarmonicFit(theta, step, 2);
  const Eigen::VectorXd k_bend = RobustHarmonicFit(theta, bend, 2);
  if (k_step.size() != 5 || k_bend.size() != 5) return m;
  m.offset_mm = std::hypot(k_step(1), k_step(2));
  m.offset_clock_rad = WrapClock(std::atan2(-k_step(2), -k_step(1)));
  // An axis turning toward clock c moves the wall there outward along the pipe (slope +α at c,
  // −α opposite). The slopes are relative to the model's centreline: add its own turn.
  const AxisFrame f0 = centreline.FrameAt(station_mm - inner - 0.5 * o.side_length_mm);
  const AxisFrame f1 = centreline.FrameAt(station_mm + inner + 0.5 * o.side_length_mm);
  const AxisFrame at = centreline.FrameAt(station_mm);
  const Eigen::Vector3d turn = f1.tangent - f0.tangent;
  const Eigen::Vector2d v(k_bend(1) + turn.dot(at.crown), k_bend(2) + turn.dot(at.right));
  m.deflection_deg = RadToDeg(std::atan(v.norm()));
  m.deflection_clock_rad = WrapClock(std::atan2(v.y(), v.x()));
  return m;
}

}  // namespace sewer3d
