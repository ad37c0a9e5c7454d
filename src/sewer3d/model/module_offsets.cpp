#include "sewer3d/model/module_offsets.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <numeric>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

// One cell's comparison of two modules: r̄_a − r̄_b = c̄_a δ_a − c̄_b δ_b, weighted by the
// inverse variance of a difference of two means (in samples).
struct Difference {
  int a = 0, b = 0;
  double ca = 1.0, cb = 1.0, d = 0.0, w = 0.0;
  [[nodiscard]] double Residual(const std::vector<double>& x) const {
    return d - (ca * x[a] - cb * x[b]);
  }
};

// Weighted least squares under Σ δ = 0 (a Lagrange multiplier: the common part is left out
// exactly, not traded against the cells).
std::vector<double> Solve(const std::vector<Difference>& diffs, int modules) {
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(modules + 1, modules + 1);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(modules + 1);
  for (const Difference& e : diffs) {
    Eigen::VectorXd j = Eigen::VectorXd::Zero(modules);
    j(e.a) = e.ca;
    j(e.b) = -e.cb;
    kkt.topLeftCorner(modules, modules) += e.w * j * j.transpose();
    rhs.head(modules) += e.w * e.d * j;
  }
  kkt.block(modules, 0, 1, modules).setOnes();
  kkt.block(0, modules, modules, 1).setOnes();
  const Eigen::VectorXd x = kkt.fullPivLu().solve(rhs);
  return {x.data(), x.data() + modules};
}

double WeightedRms(const std::vector<Difference>& diffs, const std::vector<double>& x) {
  double sw = 0.0, swe2 = 0.0;
  for (const Difference& e : diffs) {
    const double r = e.Residual(x);
    sw += e.w;
    swe2 += e.w * r * r;
  }
  return sw > 0.0 ? std::sqrt(swe2 / sw) : 0.0;
}

// Whether the pairs with enough cells join every module into one graph.
bool Connected(const std::vector<std::vector<int>>& cells, int modules, int min_cells) {
  std::vector<int> part(modules);
  std::iota(part.begin(), part.end(), 0);
  const auto root = [&](int i) {
    while (part[i] != i) i = part[i];
    return i;
  };
  for (int a = 0; a < modules; ++a)
    for (int b = a + 1; b < modules; ++b)
      if (cells[a][b] >= min_cells) part[root(a)] = root(b);
  for (int m = 1; m < modules; ++m)
    if (root(m) != root(0)) return false;
  return true;
}

// The offsets from the cells' differences (`out` has its vectors sized): the pairs with too few
// cells are left out, then two passes of Solve.
ModuleOffsets Fit(std::vector<Difference> diffs, int modules, const ModuleOffsetOptions& o,
                  ModuleOffsets out) {
  std::vector<std::vector<int>> cells(modules, std::vector<int>(modules, 0));
  for (const Difference& e : diffs) ++cells[e.a][e.b];
  for (int m = 0; m < modules; ++m) {
    const int next = (m + 1) % modules;
    out.pair_cells[m] = cells[std::min(m, next)][std::max(m, next)];
  }
  if (!Connected(cells, modules, o.min_cells)) {
    out.why = fmt::format("the modules' overlaps do not join them all ({} cells at least per pair)",
                          o.min_cells);
    return out;
  }
  std::erase_if(diffs, [&](const Difference& e) { return cells[e.a][e.b] < o.min_cells; });
  std::vector<double> x = Solve(diffs, modules);
  // Again without the cells beyond three robust sigmas (edges, features, a pose gone astray).
  std::vector<double> abs_residuals;
  for (const Difference& e : diffs) abs_residuals.push_back(std::abs(e.Residual(x)));
  auto mid = abs_residuals.begin() + static_cast<std::ptrdiff_t>(abs_residuals.size() / 2);
  std::nth_element(abs_residuals.begin(), mid, abs_residuals.end());
  const double limit = std::max(3.0 * 1.4826 * *mid, 1e-3);
  std::erase_if(diffs, [&](const Difference& e) { return std::abs(e.Residual(x)) > limit; });
  x = Solve(diffs, modules);
  out.cells = static_cast<int>(diffs.size());
  out.rms_before_mm = WeightedRms(diffs, std::vector<double>(modules, 0.0));
  out.rms_after_mm = WeightedRms(diffs, x);
  const double largest = std::abs(*std::max_element(
      x.begin(), x.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }));
  if (!(largest <= o.max_offset_mm)) {
    out.why = fmt::format("an offset of {:.2f} mm is no calibration error's (at most {} mm)",
                          largest, o.max_offset_mm);
    return out;
  }
  out.range_mm = x;
  out.estimated = true;
  return out;
}

}  // namespace

void ModuleOffsetOptions::Check() const {
  ValidatePositive("cell_mm", cell_mm);
  SEWER3D_VALIDATE(min_cell_samples >= 1, "min_cell_samples", "must be ≥ 1");
  ValidatePositive("max_difference_mm", max_difference_mm);
  SEWER3D_VALIDATE(min_cells >= 1, "min_cells", "must be ≥ 1");
  ValidatePositive("max_offset_mm", max_offset_mm);
}

ModuleOffsetEstimator::ModuleOffsetEstimator(int modules, double radius_mm,
                                             const ModuleOffsetOptions& options)
    : modules_(modules), radius_mm_(radius_mm), options_(options) {
  options.Check();
  ValidatePositive("radius_mm", radius_mm);
  clock_cells_ =
      static_cast<std::int64_t>(std::ceil(2.0 * std::numbers::pi * radius_mm / options.cell_mm));
}

void ModuleOffsetEstimator::Add(const ModuleWallSample& s) {
  if (s.module < 0 || s.module >= modules_ || !std::isfinite(s.radius_mm) ||
      !std::isfinite(s.station_mm) || !std::isfinite(s.clock_rad))
    return;
  constexpr double kTurn = 2.0 * std::numbers::pi;
  const auto row = static_cast<std::int64_t>(std::floor(s.station_mm / options_.cell_mm));
  const double clock = std::fmod(std::fmod(s.clock_rad, kTurn) + kTurn, kTurn);
  const auto col =
      std::min(clock_cells_ - 1, static_cast<std::int64_t>(clock * radius_mm_ / options_.cell_mm));
  const auto [it, added] = index_.try_emplace(row * clock_cells_ + col, sums_.size());
  if (added) sums_.resize(sums_.size() + modules_);
  Sums& c = sums_[it->second + s.module];
  c.radius += s.radius_mm;
  c.cosine += s.cos_incidence;
  ++c.n;
}

ModuleOffsets ModuleOffsetEstimator::Estimate() const {
  ModuleOffsets out;
  out.range_mm.assign(std::max(modules_, 0), 0.0);
  out.pair_cells.assign(std::max(modules_, 0), 0);
  if (modules_ < 2) {
    out.why = "fewer than two modules";
    return out;
  }
  std::vector<Difference> diffs;
  for (std::size_t cell = 0; cell < sums_.size(); cell += modules_) {
    for (int a = 0; a < modules_; ++a) {
      const Sums& sa = sums_[cell + a];
      if (sa.n < options_.min_cell_samples) continue;
      for (int b = a + 1; b < modules_; ++b) {
        const Sums& sb = sums_[cell + b];
        if (sb.n < options_.min_cell_samples) continue;
        const double d = sa.radius / sa.n - sb.radius / sb.n;
        if (std::abs(d) > options_.max_difference_mm) continue;
        diffs.push_back(
            {a, b, sa.cosine / sa.n, sb.cosine / sb.n, d, 1.0 / (1.0 / sa.n + 1.0 / sb.n)});
      }
    }
  }
  return Fit(std::move(diffs), modules_, options_, std::move(out));
}

ModuleOffsets EstimateModuleOffsets(const std::vector<ModuleWallSample>& samples, int modules,
                                    double radius_mm, const ModuleOffsetOptions& options) {
  ModuleOffsetEstimator estimator(modules, radius_mm, options);
  for (const ModuleWallSample& s : samples) estimator.Add(s);
  return estimator.Estimate();
}

}  // namespace sewer3d
