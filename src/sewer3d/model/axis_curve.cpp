#include "sewer3d/model/axis_curve.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/circle_fit.hpp"

namespace sewer3d {
namespace {

// Weighted least squares of the samples against [1, d, d²] (or [1, d]) with d = s − s0: the
// constant term is the curve at s0.
Eigen::Vector3d LocalPolynomial(const std::vector<AxisSample>& samples, double s0,
                                double half_width, int degree) {
  const int n = degree + 1;
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 3);
  for (const auto& sample : samples) {
    const double d = sample.station_mm - s0, u = std::abs(d) / half_width;
    if (u >= 1.0) continue;
    const double w = std::pow(1.0 - u * u * u, 3);
    Eigen::VectorXd basis(n);
    for (int k = 0; k < n; ++k) basis(k) = std::pow(d / half_width, k);  // scaled: conditioned
    normal += w * basis * basis.transpose();
    rhs += w * basis * sample.centre.transpose();
  }
  return normal.ldlt().solve(rhs).row(0).transpose();
}

}  // namespace

std::vector<Eigen::Vector3d> SmoothAxis(const std::vector<AxisSample>& samples,
                                        const std::vector<double>& at_stations,
                                        double half_width_mm, bool straight) {
  SEWER3D_CHECK(samples.size() >= (straight ? 2u : 3u) && half_width_mm > 0.0);
  std::vector<Eigen::Vector3d> curve;
  curve.reserve(at_stations.size());
  const double span = samples.back().station_mm - samples.front().station_mm;
  for (const double s : at_stations) {
    if (straight) {  // one line over everything: an infinitely wide window of degree 1
      curve.push_back(LocalPolynomial(samples, s, 4.0 * (span + std::abs(s) + 1.0), 1));
      continue;
    }
    double h = half_width_mm;
    auto in_window = [&] {
      return std::count_if(samples.begin(), samples.end(),
                           [&](const AxisSample& a) { return std::abs(a.station_mm - s) < h; });
    };
    while (in_window() < 4 && h < 4.0 * (span + std::abs(s) + 1.0)) h *= 1.5;
    curve.push_back(LocalPolynomial(samples, s, h, in_window() >= 4 ? 2 : 1));
  }
  return curve;
}

std::optional<Centreline> ResampleAxis(const std::vector<Eigen::Vector3d>& curve, double step_mm) {
  SEWER3D_CHECK(step_mm > 0.0);
  if (curve.size() < 2) return std::nullopt;
  std::vector<double> arc(curve.size(), 0.0);
  for (std::size_t j = 1; j < curve.size(); ++j)
    arc[j] = arc[j - 1] + (curve[j] - curve[j - 1]).norm();
  if (!(arc.back() > 0.0)) return std::nullopt;
  // Arc length where the curve passes z = 0.
  double zero_arc = 0.0;
  const auto cross = std::adjacent_find(
      curve.begin(), curve.end(),
      [](const auto& a, const auto& b) { return (a.z() <= 0.0) != (b.z() <= 0.0); });
  if (cross != curve.end()) {
    const auto j = static_cast<std::size_t>(cross - curve.begin());
    const double w = curve[j].z() / (curve[j].z() - curve[j + 1].z());
    zero_arc = arc[j] + w * (arc[j + 1] - arc[j]);
  } else {
    const bool before = std::abs(curve.front().z()) < std::abs(curve.back().z());
    const std::size_t j = before ? 0 : curve.size() - 2;
    const Eigen::Vector3d t = (curve[j + 1] - curve[j]) / (arc[j + 1] - arc[j]);
    if (std::abs(t.z()) < 1e-6) return std::nullopt;
    const std::size_t end = before ? 0 : curve.size() - 1;
    zero_arc = arc[end] - curve[end].z() / t.z();
  }
  Centreline line;
  line.step_mm = step_mm;
  const auto k0 = static_cast<long>(std::floor((arc.front() - zero_arc) / step_mm));
  const auto k1 = static_cast<long>(std::ceil((arc.back() - zero_arc) / step_mm));
  line.station0_mm = static_cast<double>(k0) * step_mm;
  std::size_t j = 0;
  for (long k = k0; k <= k1; ++k) {
    const double a = zero_arc + static_cast<double>(k) * step_mm;
    while (j + 2 < curve.size() && arc[j + 1] < a) ++j;
    const double w = (a - arc[j]) / (arc[j + 1] - arc[j]);  // extrapolates at the ends
    line.points.push_back((1.0 - w) * curve[j] + w * curve[j + 1]);
  }
  for (std::size_t i = 0; i < line.points.size(); ++i) {
    const Eigen::Vector3d t = line.TangentAt(i), up = -Eigen::Vector3d::UnitY();
    const Eigen::Vector3d crown = up - up.dot(t) * t;
    if (crown.norm() < 1e-6) return std::nullopt;
    line.crowns.push_back(crown.normalized());
  }
  return line;
}

std::optional<double> FitBendRadius(const Centreline& centreline, double min_sagitta_mm) {
  const auto& p = centreline.points;
  if (p.size() < 3) return std::nullopt;
  const Eigen::Vector3d chord = (p.back() - p.front()).normalized();
  double sagitta = 0.0;
  for (const auto& x : p) {
    const Eigen::Vector3d d = x - p.front();
    sagitta = std::max(sagitta, (d - d.dot(chord) * chord).norm());
  }
  if (sagitta < min_sagitta_mm) return std::nullopt;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& x : p) mean += x;
  mean /= static_cast<double>(p.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& x : p) scatter += (x - mean) * (x - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  const Eigen::Vector3d e1 = eig.eigenvectors().col(2), e2 = eig.eigenvectors().col(1);
  std::vector<Eigen::Vector2d> in_plane;
  for (const auto& x : p) in_plane.emplace_back((x - mean).dot(e1), (x - mean).dot(e2));
  CircleFitOptions options;
  options.model_ovality = false;
  options.min_scale_mm = 1e-3;
  const CircleFit fit = FitCircleRobust(in_plane, options);
  if (!fit.converged) return std::nullopt;
  return fit.radius_mm;
}

}  // namespace sewer3d
