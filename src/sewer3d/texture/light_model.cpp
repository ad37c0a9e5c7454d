#include "sewer3d/texture/light_model.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

// Monomials x^a y^b with a + b ≤ degree.
Eigen::VectorXd Terms(double x, double y, int degree) {
  Eigen::VectorXd t((degree + 1) * (degree + 2) / 2);
  int k = 0;
  for (int d = 0; d <= degree; ++d) {
    for (int a = d; a >= 0; --a) t(k++) = std::pow(x, a) * std::pow(y, d - a);
  }
  return t;
}

double CellX(int i, int cols) { return cols > 1 ? 2.0 * i / (cols - 1) - 1.0 : 0.0; }

}  // namespace

double FitSmoothLight(std::vector<double>& grid, const std::vector<bool>& known, int cols, int rows,
                      int degree, double huber_log2) {
  SEWER3D_VALIDATE(degree >= 1 && degree <= 6, "degree", "must be 1..6, got " << degree);
  ValidatePositive("huber_log2", huber_log2);
  SEWER3D_VALIDATE(grid.size() == static_cast<size_t>(cols) * rows && known.size() == grid.size(),
                   "grid", "must hold cols x rows cells");
  const int terms = (degree + 1) * (degree + 2) / 2;
  std::vector<int> cells;
  for (int c = 0; c < cols * rows; ++c) {
    if (known[c]) cells.push_back(c);
  }
  if (static_cast<int>(cells.size()) < terms) return -1.0;
  Eigen::MatrixXd a(cells.size(), terms);
  Eigen::VectorXd b(cells.size()), w = Eigen::VectorXd::Ones(cells.size());
  for (size_t k = 0; k < cells.size(); ++k) {
    a.row(k) = Terms(CellX(cells[k] % cols, cols), CellX(cells[k] / cols, rows), degree);
    b(k) = grid[cells[k]];
  }
  Eigen::VectorXd coefficients;
  Eigen::VectorXd residual;
  for (int iteration = 0; iteration < 10; ++iteration) {
    const Eigen::MatrixXd aw = w.asDiagonal() * a;
    coefficients = (a.transpose() * aw).ldlt().solve(aw.transpose() * b);
    residual = a * coefficients - b;
    for (int k = 0; k < residual.size(); ++k) {
      const double r = std::abs(residual(k));
      w(k) = r <= huber_log2 ? 1.0 : huber_log2 / r;
    }
  }
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i)
      grid[j * cols + i] = Terms(CellX(i, cols), CellX(j, rows), degree).dot(coefficients);
  }
  return std::sqrt(residual.squaredNorm() / static_cast<double>(residual.size()));
}

}  // namespace sewer3d
