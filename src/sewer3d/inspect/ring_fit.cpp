#include "sewer3d/inspect/ring_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "sewer3d/core/check.hpp"
#include "sewer3d/inspect/robust_stats.hpp"

namespace sewer3d {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Eigen::VectorXd Basis(double theta, int order) {
  Eigen::VectorXd b(1 + 2 * order);
  b(0) = 1.0;
  for (int k = 1; k <= order; ++k) {
    b(2 * k - 1) = std::cos(k * theta);
    b(2 * k) = std::sin(k * theta);
  }
  return b;
}

}  // namespace

double RingValue(const RingCoefficients& k, double theta_rad) {
  return k(0) + k(1) * std::cos(theta_rad) + k(2) * std::sin(theta_rad) +
         k(3) * std::cos(2.0 * theta_rad) + k(4) * std::sin(2.0 * theta_rad);
}

Eigen::VectorXd RobustHarmonicFit(const std::vector<double>& theta_rad,
                                  const std::vector<double>& values, int order) {
  SEWER3D_CHECK(theta_rad.size() == values.size() && (order == 1 || order == 2));
  const int n = static_cast<int>(values.size()), p = 1 + 2 * order;
  if (n < 2 * p) return {};
  Eigen::VectorXd k = Eigen::VectorXd::Zero(p);
  k(0) = Median(values);
  std::vector<double> abs_res(n);
  for (int iter = 0; iter < 10; ++iter) {
    for (int i = 0; i < n; ++i)
      abs_res[i] = std::abs(values[i] - Basis(theta_rad[i], order).dot(k));
    const double c = 4.685 * std::max(0.01, 1.4826 * Median(abs_res));
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(p, p);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(p);
    for (int i = 0; i < n; ++i) {
      const double u = abs_res[i] / c;
      if (u >= 1.0) continue;
      const double w = (1.0 - u * u) * (1.0 - u * u);
      const Eigen::VectorXd b = Basis(theta_rad[i], order);
      a.noalias() += w * b * b.transpose();
      rhs += w * values[i] * b;
    }
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(a);
    if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-9) return {};
    const Eigen::VectorXd next = ldlt.solve(rhs);
    const double change = (next - k).cwiseAbs().maxCoeff();
    k = next;
    if (change < 1e-4) break;
  }
  return k;
}

namespace {

/// Second pass for rows measured over less than min_coverage but at least a third of the turn:
/// the 2θ terms of the nearest fully fitted row (within max_rows), a0 and the axis terms fitted.
void FitPartialRings(const CoarseMap& map, const std::vector<double>& theta, int max_rows,
                     std::vector<RingFit>& fits) {
  const cv::Mat1f& d = map.displacement_mm;
  std::vector<int> full;
  for (int r = 0; r < d.rows; ++r) {
    if (fits[r].valid) full.push_back(r);
  }
  std::vector<double> th, v;
  for (int r = 0; r < d.rows; ++r) {
    if (fits[r].valid || fits[r].coverage < 1.0 / 3.0 || full.empty()) continue;
    const auto it = std::lower_bound(full.begin(), full.end(), r);
    int near = it == full.end() ? full.back() : *it;
    if (it != full.begin() && (it == full.end() || r - *(it - 1) < *it - r)) near = *(it - 1);
    if (std::abs(near - r) > max_rows) continue;
    const RingCoefficients& k2 = fits[near].k;
    th.clear();
    v.clear();
    for (int c = 0; c < d.cols; ++c) {
      if (!std::isfinite(d(r, c))) continue;
      th.push_back(theta[c]);
      v.push_back(d(r, c) - k2(3) * std::cos(2.0 * theta[c]) - k2(4) * std::sin(2.0 * theta[c]));
    }
    const Eigen::VectorXd k = RobustHarmonicFit(th, v, 1);
    if (k.size() != 3) continue;
    fits[r].k << k(0), k(1), k(2), k2(3), k2(4);
    fits[r].valid = true;
  }
}

}  // namespace

std::vector<RingFit> FitRings(const CoarseMap& map, double min_coverage) {
  const cv::Mat1f& d = map.displacement_mm;
  std::vector<double> theta(d.cols);
  for (int c = 0; c < d.cols; ++c) theta[c] = map.ColClockRad(c);
  std::vector<RingFit> fits(d.rows);
  std::vector<double> th, v;
  for (int r = 0; r < d.rows; ++r) {
    th.clear();
    v.clear();
    for (int c = 0; c < d.cols; ++c) {
      if (!std::isfinite(d(r, c))) continue;
      th.push_back(theta[c]);
      v.push_back(d(r, c));
    }
    RingFit& f = fits[r];
    f.coverage = static_cast<double>(v.size()) / d.cols;
    f.k(0) = Median(v);
    if (f.coverage < min_coverage) continue;
    const Eigen::VectorXd k = RobustHarmonicFit(th, v, 2);
    if (k.size() != 5) continue;
    f.k = k;
    f.valid = true;
  }
  FitPartialRings(map, theta, static_cast<int>(300.0 / map.RowMm()), fits);
  return fits;
}

std::vector<RingCoefficients> SmoothRings(const std::vector<RingFit>& fits,
                                          const std::vector<RowRange>& sections, int half_rows) {
  RingCoefficients nan;
  nan.setConstant(kNaN);
  std::vector<RingCoefficients> out(fits.size(), nan);
  std::vector<double> window;
  for (const RowRange& s : sections) {
    std::vector<int> valid;
    for (int r = s.begin; r < s.end; ++r) {
      if (fits[r].valid) valid.push_back(r);
    }
    if (valid.empty()) continue;
    for (int r = s.begin; r < s.end; ++r) {
      // Nearest valid row, then the median of the valid rows within ± half_rows of it.
      const auto it = std::lower_bound(valid.begin(), valid.end(), r);
      int centre = it == valid.end() ? valid.back() : *it;
      if (it != valid.begin() && (it == valid.end() || r - *(it - 1) < *it - r)) centre = *(it - 1);
      if (std::abs(centre - r) > half_rows) continue;  // no fit near enough: not inspected
      const auto lo = std::lower_bound(valid.begin(), valid.end(), centre - half_rows);
      const auto hi = std::upper_bound(valid.begin(), valid.end(), centre + half_rows);
      for (int j = 0; j < 5; ++j) {
        window.clear();
        for (auto v = lo; v != hi; ++v) window.push_back(fits[*v].k(j));
        out[r](j) = Median(window);
      }
    }
  }
  return out;
}

cv::Mat1f RingResidual(const CoarseMap& map, const std::vector<RingCoefficients>& rings) {
  const cv::Mat1f& d = map.displacement_mm;
  SEWER3D_CHECK(static_cast<int>(rings.size()) == d.rows);
  cv::Mat1f out(d.size());
  for (int c = 0; c < d.cols; ++c) {
    const double theta = map.ColClockRad(c);
    for (int r = 0; r < d.rows; ++r) {
      out(r, c) = static_cast<float>(d(r, c) - RingValue(rings[r], theta));
    }
  }
  return out;
}

double RobustSigma(const cv::Mat1f& m) {
  std::vector<double> v;
  for (int r = 0; r < m.rows; ++r) {
    for (int c = 0; c < m.cols; ++c) {
      if (std::isfinite(m(r, c))) v.push_back(m(r, c));
    }
  }
  if (v.empty()) return 0.0;
  const double med = Median(v);
  for (double& x : v) x = std::abs(x - med);
  return 1.4826 * Median(v);
}

}  // namespace sewer3d
