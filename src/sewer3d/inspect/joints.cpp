#include "sewer3d/inspect/joints.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "sewer3d/core/check.hpp"
#include "sewer3d/inspect/robust_stats.hpp"

namespace sewer3d {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Per row: among the clock columns measured on both sides within ± w rows, the share where
/// the row is missing or lies more than min_depth_mm deeper than the column's median there.
std::vector<double> GapShare(const cv::Mat1f& d, int w, double min_depth_mm) {
  std::vector<double> share(d.rows, 0.0);
  std::vector<int> open(d.rows, 0), known(d.rows, 0);
  std::vector<int> prefix(d.rows + 1);
  std::vector<double> window;
  for (int c = 0; c < d.cols; ++c) {
    for (int r = 0; r < d.rows; ++r) prefix[r + 1] = prefix[r] + (std::isfinite(d(r, c)) ? 1 : 0);
    auto finite = [&](int from, int to) {  // finite cells in rows [from, to)
      return prefix[std::clamp(to, 0, d.rows)] - prefix[std::clamp(from, 0, d.rows)];
    };
    for (int r = 0; r < d.rows; ++r) {
      if (finite(r - w, r) == 0 || finite(r + 1, r + 1 + w) == 0) continue;
      ++known[r];
      if (!std::isfinite(d(r, c))) {
        ++open[r];
        continue;
      }
      window.clear();
      for (int j = std::max(0, r - w); j <= std::min(d.rows - 1, r + w); ++j) {
        if (std::isfinite(d(j, c))) window.push_back(d(j, c));
      }
      if (d(r, c) - Median(window) > min_depth_mm) ++open[r];
    }
  }
  for (int r = 0; r < d.rows; ++r) {
    if (3 * known[r] >= d.cols) share[r] = static_cast<double>(open[r]) / known[r];
  }
  return share;
}

struct Candidate {
  double row = 0.0;  ///< fractional coarse row of the centre
  double gap_rows = 0.0;
};

/// Runs of rows open around most of the turn, no wider than a joint gap.
std::vector<Candidate> GapCandidates(const std::vector<double>& share, const JointOptions& o,
                                     double row_mm) {
  std::vector<Candidate> out;
  const int n = static_cast<int>(share.size());
  for (int r = 0; r < n;) {
    if (share[r] < o.min_gap_share) {
      ++r;
      continue;
    }
    int end = r;
    double area = 0.0, moment = 0.0;
    while (end < n && share[end] >= o.min_gap_share) {
      area += share[end];
      moment += share[end] * end;
      ++end;
    }
    if ((end - r) * row_mm <= o.max_gap_mm + 2.0 * row_mm) out.push_back({moment / area, area});
    r = end;
  }
  return out;
}

/// Rows where the axis-offset terms (c1, s1) of the valid ring fits jump by ≥ min_offset_mm
/// between the side_length_mm before and after, away from the gaps already found.
std::vector<Candidate> StepCandidates(const std::vector<RingFit>& fits, const JointOptions& o,
                                      double row_mm, const std::vector<Candidate>& gaps) {
  const int n = static_cast<int>(fits.size());
  const int len = std::max(3, static_cast<int>(o.side_length_mm / row_mm));
  const int margin = static_cast<int>(std::ceil(o.side_margin_mm / row_mm));
  std::vector<double> jump(n, 0.0);
  // The axis terms of the valid rows in [from, to), fitted by a line and evaluated at `at`.
  auto side = [&](int from, int to, int at) {
    Eigen::Matrix2d a = Eigen::Matrix2d::Zero();
    Eigen::Matrix2d rhs = Eigen::Matrix2d::Zero();  // columns: c1, s1
    int count = 0;
    for (int j = std::max(0, from); j < std::min(n, to); ++j) {
      if (!fits[j].valid) continue;
      const Eigen::Vector2d b(1.0, j - at);
      a += b * b.transpose();
      rhs.col(0) += fits[j].k(1) * b;
      rhs.col(1) += fits[j].k(2) * b;
      ++count;
    }
    if (2 * count < to - from || a.determinant() <= 0.0) return Eigen::Vector2d(kNaN, kNaN);
    const Eigen::Matrix2d k = a.ldlt().solve(rhs);
    return Eigen::Vector2d(k(0, 0), k(0, 1));
  };
  for (int r = 0; r < n; ++r) {
    const Eigen::Vector2d d =
        side(r + margin, r + margin + len, r) - side(r - margin - len, r - margin, r);
    jump[r] = d.allFinite() ? d.norm() : 0.0;
  }
  std::vector<Candidate> out;
  for (int r = 0; r < n; ++r) {
    if (jump[r] < o.min_offset_mm) continue;
    bool peak = true;
    for (int j = std::max(0, r - len); j <= std::min(n - 1, r + len) && peak; ++j) {
      peak = jump[j] < jump[r] || (jump[j] == jump[r] && j >= r);
    }
    bool near_gap = false;
    for (const Candidate& gap : gaps) near_gap = near_gap || std::abs(gap.row - r) <= len;
    if (peak && !near_gap) out.push_back({static_cast<double>(r), 0.0});
  }
  return out;
}

}  // namespace

void JointOptions::Check() const {
  ValidatePositive("min_gap_depth_mm", min_gap_depth_mm);
  ValidatePositive("max_gap_mm", max_gap_mm);
  ValidatePositive("min_offset_mm", min_offset_mm);
  ValidatePositive("side_length_mm", side_length_mm);
  ValidateNotNegative("side_margin_mm", side_margin_mm);
  ValidateNotNegative("unseen_gap_mm", unseen_gap_mm);
  ValidateNotNegative("gap_reach_mm", gap_reach_mm);
  ValidatePositive("max_side_rms_factor", max_side_rms_factor);
  SEWER3D_VALIDATE(min_gap_share > 0.0 && min_gap_share <= 1.0, "min_gap_share",
                   "must be in (0, 1], got " << min_gap_share);
  SEWER3D_VALIDATE(min_open_share >= 0.0 && min_open_share <= 1.0, "min_open_share",
                   "must be in [0, 1], got " << min_open_share);
}

std::vector<JointMeasure> FindJoints(const CoarseMap& map, const std::vector<RingFit>& fits,
                                     const Centreline& centreline, const JointOptions& options) {
  options.Check();
  SEWER3D_CHECK(static_cast<int>(fits.size()) == map.displacement_mm.rows);
  const double row_mm = map.RowMm();
  const int half = std::max(3, static_cast<int>((0.5 * options.max_gap_mm + 5.0) / row_mm));
  const std::vector<double> share = GapShare(map.displacement_mm, half, options.min_gap_depth_mm);
  std::vector<Candidate> all = GapCandidates(share, options, row_mm);
  const std::vector<Candidate> steps = StepCandidates(fits, options, row_mm, all);
  all.insert(all.end(), steps.begin(), steps.end());
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.row < b.row; });
  std::vector<JointMeasure> out;
  for (const Candidate& c : all) {
    const double station = map.fine.station0_mm + (c.row + 0.5) * row_mm;
    JointMeasure m = MeasureJoint(map, centreline, station, c.gap_rows * row_mm, options);
    if (c.gap_rows == 0.0 && m.offset_mm < options.min_offset_mm) continue;  // no step after all
    out.push_back(m);
  }
  return out;
}

}  // namespace sewer3d
