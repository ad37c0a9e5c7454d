#include "sewer3d/pattern/constraints.hpp"

#include <algorithm>
#include <bit>
#include <sstream>
#include <vector>

namespace sewer3d {

void PatternConstraints::Check() const {
  SEWER3D_VALIDATE(window >= 2 && window <= 8, "window", "must be 2..8, got " << window);
  SEWER3D_VALIDATE(min_hamming >= 1 && min_hamming <= window * window, "min_hamming",
                   "must be 1.." << window * window << ", got " << min_hamming);
  SEWER3D_VALIDATE(min_weight >= 0 && min_weight <= window * window, "min_weight",
                   "must be 0.." << window * window << ", got " << min_weight);
  // Isolated spots (no two 8-adjacent) fit at most ceil(n/2)² in an n x n window.
  const int most_isolated = ((window + 1) / 2) * ((window + 1) / 2);
  SEWER3D_VALIDATE(!isolated || min_weight <= most_isolated, "min_weight",
                   "isolated spots fit at most " << most_isolated << " in a " << window << "x"
                                                 << window << " window, got " << min_weight);
}

int WindowCount(int rows, int cols, const PatternConstraints& constraints) {
  if (constraints.torus) return rows * cols;
  return std::max(0, rows - constraints.window + 1) * std::max(0, cols - constraints.window + 1);
}

PatternReport VerifyPattern(const BinaryArray& array, const PatternConstraints& constraints) {
  constraints.Check();
  PatternReport report;
  report.rows = array.rows;
  report.cols = array.cols;
  const int n = constraints.window;
  const int win_rows = constraints.torus ? array.rows : array.rows - n + 1;
  const int win_cols = constraints.torus ? array.cols : array.cols - n + 1;
  std::vector<std::uint64_t> codes;
  for (int r = 0; r < win_rows; ++r) {
    for (int c = 0; c < win_cols; ++c) codes.push_back(TiledWindowCode(array, r, c, n));
  }
  report.windows = static_cast<int>(codes.size());
  report.min_hamming_found = n * n + 1;
  report.min_weight_found = codes.empty() ? 0 : n * n;
  for (size_t a = 0; a < codes.size(); ++a) {
    const int weight = std::popcount(codes[a]);
    report.min_weight_found = std::min(report.min_weight_found, weight);
    report.max_weight_found = std::max(report.max_weight_found, weight);
    for (size_t b = a + 1; b < codes.size(); ++b) {
      const int d = std::popcount(codes[a] ^ codes[b]);
      report.min_hamming_found = std::min(report.min_hamming_found, d);
      if (d == 0) ++report.duplicate_pairs;
      if (d < constraints.min_hamming) ++report.close_pairs;
    }
  }
  // Adjacency: count each unordered pair once via the four "forward" neighbours.
  const int kForward[4][2] = {{0, 1}, {1, -1}, {1, 0}, {1, 1}};
  for (int r = 0; r < array.rows; ++r) {
    for (int c = 0; c < array.cols; ++c) {
      if (!array.at(r, c)) continue;
      for (const auto& d : kForward) {
        const int rr = r + d[0], cc = c + d[1];
        const bool inside = rr >= 0 && rr < array.rows && cc >= 0 && cc < array.cols;
        if (!inside && !constraints.torus) continue;
        if (array.tiled(rr, cc)) ++report.adjacent_spot_pairs;
      }
    }
  }
  report.density = array.bits.empty() ? 0.0 : double(array.Weight()) / array.bits.size();
  report.valid = report.windows > 0 && report.close_pairs == 0 &&
                 report.min_weight_found >= constraints.min_weight &&
                 (!constraints.isolated || report.adjacent_spot_pairs == 0);
  return report;
}

PatternConstraints InferConstraints(const BinaryArray& array, int window) {
  PatternConstraints c;
  c.window = window;
  c.min_hamming = 1;
  c.min_weight = 0;
  c.isolated = false;
  PatternReport report = VerifyPattern(array, c);
  if (report.duplicate_pairs > 0 || report.windows == 0) {
    c.torus = false;
    report = VerifyPattern(array, c);
  }
  SEWER3D_VALIDATE(report.windows > 0 && report.duplicate_pairs == 0, "",
                   "the pattern's " << window << "x" << window << " windows are not unique");
  c.min_hamming = std::min(report.min_hamming_found, window * window);  // one window: no pair
  c.min_weight = report.min_weight_found;
  c.isolated = report.adjacent_spot_pairs == 0;
  return c;
}

std::string Describe(const PatternReport& r) {
  std::ostringstream out;
  out << r.rows << "x" << r.cols << ", " << r.windows << " windows, min Hamming ";
  if (r.windows < 2) {
    out << "- (no pair)";
  } else {
    out << r.min_hamming_found;
  }
  out << ", weight " << r.min_weight_found << ".." << r.max_weight_found << ", adjacent spot pairs "
      << r.adjacent_spot_pairs << ", density " << r.density
      << (r.valid ? " (valid)" : " (INVALID)");
  return out.str();
}

}  // namespace sewer3d
