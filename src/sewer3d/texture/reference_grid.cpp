#include "sewer3d/texture/reference_grid.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace sewer3d::reference_grid {

void FillHoles(Grid& g, const std::vector<bool>& known, int cols, int rows) {
  double sum = 0.0;
  int n = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    if (known[i]) sum += g[i], ++n;
  }
  for (size_t i = 0; i < g.size(); ++i) {
    if (!known[i]) g[i] = sum / n;
  }
  if (n == static_cast<int>(g.size())) return;
  for (int iteration = 0; iteration < 10000; ++iteration) {
    double change = 0.0;
    for (int j = 0; j < rows; ++j) {
      for (int i = 0; i < cols; ++i) {
        if (known[j * cols + i]) continue;
        double s = 0.0;
        int m = 0;
        if (i > 0) s += g[j * cols + i - 1], ++m;
        if (i + 1 < cols) s += g[j * cols + i + 1], ++m;
        if (j > 0) s += g[(j - 1) * cols + i], ++m;
        if (j + 1 < rows) s += g[(j + 1) * cols + i], ++m;
        if (m == 0) continue;
        change = std::max(change, std::abs(s / m - g[j * cols + i]));
        g[j * cols + i] = s / m;
      }
    }
    if (change < 1e-6) break;
  }
}

void SmoothQuadratic(Grid& g, int cols, int rows, int half_width) {
  const auto pass = [&](int n, int lines, int stride, int line_stride) {
    const int window = std::min(n, 2 * half_width + 1);
    if (window < 2) return;
    const int degree = std::min(2, window - 1);
    // Weights of the fitted value at k (the constant term of the fit centred on k).
    std::vector<int> first(n);
    std::vector<Eigen::VectorXd> weights(n);
    for (int k = 0; k < n; ++k) {
      first[k] = std::clamp(k - half_width, 0, n - window);
      Eigen::MatrixXd a(window, degree + 1);
      for (int i = 0; i < window; ++i) {
        for (int d = 0; d <= degree; ++d) a(i, d) = std::pow(first[k] + i - k, d);
      }
      weights[k] = (a.transpose() * a).ldlt().solve(a.transpose()).row(0).transpose();
    }
    std::vector<double> out(n);
    for (int line = 0; line < lines; ++line) {
      double* base = g.data() + static_cast<std::ptrdiff_t>(line) * line_stride;
      for (int k = 0; k < n; ++k) {
        out[k] = 0.0;
        for (int i = 0; i < window; ++i) out[k] += weights[k][i] * base[(first[k] + i) * stride];
      }
      for (int k = 0; k < n; ++k) base[k * stride] = out[k];
    }
  };
  pass(cols, rows, 1, cols);
  pass(rows, cols, cols, 1);
}

std::optional<double> TrimmedMeanLog2(const std::uint32_t* h, int bins, std::uint64_t total,
                                      double trim) {
  const double lo = trim * static_cast<double>(total);
  const double hi = std::max(lo, (1.0 - trim) * static_cast<double>(total));
  if (hi == lo) {  // the median
    double below = 0.0;
    int b = 0;
    while (below + h[b] < lo) below += h[b++];
    if (b == 0 || b == bins - 1) return std::nullopt;
    return b - 1 + (lo - below) / h[b];
  }
  double below = 0.0, mass = 0.0, sum = 0.0;
  for (int b = 0; b < bins && below < hi; ++b) {
    const double from = std::max(below, lo), to = std::min(below + h[b], hi);
    if (to > from) {
      if (b == 0 || b == bins - 1) return std::nullopt;
      mass += to - from;
      sum += (to - from) * (b - 0.5);  // bin b covers [b − 1, b) in bins from log2_min
    }
    below += h[b];
  }
  if (mass <= 0.0) return std::nullopt;
  return sum / mass;
}

}  // namespace sewer3d::reference_grid
