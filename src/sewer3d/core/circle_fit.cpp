#include "sewer3d/core/circle_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

using Vector5d = Eigen::Matrix<double, 5, 1>;

// Kåsa: x² + y² + D x + E y + F = 0 in linear least squares; the centre is (−D/2, −E/2).
bool KasaFit(const std::vector<Eigen::Vector2d>& points, Vector5d& params) {
  Eigen::MatrixXd m(points.size(), 3);
  Eigen::VectorXd rhs(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    m.row(static_cast<Eigen::Index>(i)) << points[i].x(), points[i].y(), 1.0;
    rhs(static_cast<Eigen::Index>(i)) = -points[i].squaredNorm();
  }
  const Eigen::Vector3d def = m.colPivHouseholderQr().solve(rhs);
  const double cx = -def(0) / 2, cy = -def(1) / 2, r2 = cx * cx + cy * cy - def(2);
  if (!(r2 > 0.0) || !std::isfinite(r2)) return false;
  params << cx, cy, std::sqrt(r2), 0.0, 0.0;
  return true;
}

// Residual e = |p − c| − R − a cos 2φ − b sin 2φ and its gradient in (cx, cy, R, a, b).
double Residual(const Eigen::Vector2d& p, const Vector5d& x, Vector5d* gradient) {
  const Eigen::Vector2d v = p - x.head<2>();
  const double rho = std::max(v.norm(), 1e-12), phi = std::atan2(v.y(), v.x());
  const double c2 = std::cos(2 * phi), s2 = std::sin(2 * phi);
  if (gradient != nullptr) {
    // dφ/dc = (v_y, −v_x)/ρ²; d(a cos 2φ + b sin 2φ)/dφ = −2a sin 2φ + 2b cos 2φ.
    const double dh = -2 * x(3) * s2 + 2 * x(4) * c2;
    const Eigen::Vector2d dphi(v.y() / (rho * rho), -v.x() / (rho * rho));
    gradient->head<2>() = -v / rho - dh * dphi;
    (*gradient)(2) = -1.0;
    (*gradient)(3) = -c2;
    (*gradient)(4) = -s2;
  }
  return rho - x(2) - x(3) * c2 - x(4) * s2;
}

double Median(std::vector<double> values) {
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

// Least median of squares start (Rousseeuw 1984). About the Kåsa centre c0 the wall is, to
// first order in |Δc|/R, linear in (R, Δc, a, b): ρ = R + Δcx cos θ + Δcy sin θ + a cos 2θ +
// b sin 2θ. Minimal subsets take one point from each of n equal angular sectors (well
// conditioned); the subset whose fit has the least median |residual| wins. Breakdown 50 %.
bool LmedsStart(const std::vector<Eigen::Vector2d>& points, int n, int samples, Vector5d& x) {
  const Eigen::Vector2d c0 = x.head<2>();
  Eigen::MatrixXd basis(static_cast<Eigen::Index>(points.size()), n);
  Eigen::VectorXd rho(static_cast<Eigen::Index>(points.size()));
  std::vector<std::vector<std::size_t>> sectors(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d v = points[i] - c0;
    const double t = std::atan2(v.y(), v.x());
    const auto row = static_cast<Eigen::Index>(i);
    rho(row) = v.norm();
    const double values[5] = {1.0, std::cos(t), std::sin(t), std::cos(2 * t), std::sin(2 * t)};
    for (int k = 0; k < n; ++k) basis(row, k) = values[k];
    const auto sector =
        static_cast<std::size_t>((t + std::numbers::pi) / (2 * std::numbers::pi) * n);
    sectors[std::min(sector, sectors.size() - 1)].push_back(i);
  }
  std::mt19937 rng(1);  // deterministic: the same slice gives the same fit
  std::uniform_int_distribution<std::size_t> any(0, points.size() - 1);
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> abs_e(points.size());
  for (int sample = 0; sample < samples; ++sample) {
    Eigen::MatrixXd m(n, n);
    Eigen::VectorXd rhs(n);
    for (int k = 0; k < n; ++k) {
      const auto& sector = sectors[static_cast<std::size_t>(k)];
      const std::size_t i = sector.empty() ? any(rng) : sector[rng() % sector.size()];
      m.row(k) = basis.row(static_cast<Eigen::Index>(i));
      rhs(k) = rho(static_cast<Eigen::Index>(i));
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(m);
    if (!lu.isInvertible()) continue;
    const Eigen::VectorXd params = lu.solve(rhs);
    const Eigen::VectorXd e = rho - basis * params;
    for (std::size_t i = 0; i < points.size(); ++i)
      abs_e[i] = std::abs(e(static_cast<Eigen::Index>(i)));
    const double median = Median(abs_e);
    if (median < best) {
      best = median;
      x.setZero();
      x << c0 + params.segment<2>(1), params(0), 0.0, 0.0;
      if (n == 5) x.tail<2>() = params.tail<2>();
    }
  }
  return std::isfinite(best);
}

}  // namespace

void CircleFitOptions::Check() const {
  ValidatePositive("min_scale_mm", min_scale_mm);
  ValidatePositive("tukey_c", tukey_c);
  SEWER3D_VALIDATE(lmeds_samples >= 1, "lmeds_samples", "must be >= 1, got " << lmeds_samples);
  SEWER3D_VALIDATE(iterations >= 1, "iterations", "must be >= 1, got " << iterations);
}

CircleFit FitCircleRobust(const std::vector<Eigen::Vector2d>& points,
                          const CircleFitOptions& options, std::vector<std::uint8_t>* inliers) {
  options.Check();
  if (inliers != nullptr) inliers->assign(points.size(), 0);
  CircleFit fit;
  Vector5d x;
  const int n_params = options.model_ovality ? 5 : 3;
  if (points.size() < 8 || !KasaFit(points, x) ||
      !LmedsStart(points, n_params, options.lmeds_samples, x))
    return fit;
  std::vector<double> e(points.size()), w(points.size());
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    for (std::size_t i = 0; i < points.size(); ++i) e[i] = Residual(points[i], x, nullptr);
    std::vector<double> abs_e(e.size());
    std::transform(e.begin(), e.end(), abs_e.begin(), [](double v) { return std::abs(v); });
    fit.scale_mm = std::max(1.4826 * Median(abs_e), options.min_scale_mm);
    Eigen::Matrix<double, 5, 5> normal = Eigen::Matrix<double, 5, 5>::Zero();
    Vector5d rhs = Vector5d::Zero();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double u = std::abs(e[i]) / fit.scale_mm;
      w[i] = u < options.tukey_c ? std::pow(1 - std::pow(u / options.tukey_c, 2), 2) : 0.0;
      Vector5d g;
      Residual(points[i], x, &g);
      normal += w[i] * g * g.transpose();
      rhs -= w[i] * g * e[i];
    }
    const auto block = normal.topLeftCorner(n_params, n_params);
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(block);
    if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-12)) return fit;
    const Eigen::VectorXd delta = ldlt.solve(rhs.head(n_params));
    x.head(n_params) += delta;
    if (delta.norm() < 1e-7) break;
  }
  // Final statistics on the final parameters.
  double sum2 = 0.0;
  int kept = 0;
  std::array<bool, 36> bins{};
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double r = Residual(points[i], x, nullptr);
    if (std::abs(r) >= options.tukey_c * fit.scale_mm) continue;
    if (inliers != nullptr) (*inliers)[i] = 1;
    ++kept, sum2 += r * r;
    const Eigen::Vector2d v = points[i] - x.head<2>();
    const double phi = std::atan2(v.y(), v.x()) + std::numbers::pi;
    bins[std::min<std::size_t>(35, static_cast<std::size_t>(phi / (2 * std::numbers::pi) * 36))] =
        true;
  }
  fit.centre = x.head<2>();
  fit.radius_mm = x(2);
  fit.ovality_mm = std::hypot(x(3), x(4));
  fit.inlier_fraction = static_cast<double>(kept) / static_cast<double>(points.size());
  fit.rms_mm = kept > 0 ? std::sqrt(sum2 / kept) : 0.0;
  fit.coverage_deg = 10.0 * static_cast<double>(std::count(bins.begin(), bins.end(), true));
  fit.converged = x.allFinite() && kept >= n_params + 3 && fit.radius_mm > 0.0;
  return fit;
}

}  // namespace sewer3d
