#include "sewer3d/inspect/coarse_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

double CoarseMap::RowStationMm(int row) const {
  const int first = FineRow(row), last = std::min(fine.rows, first + factor);
  return fine.station0_mm + 0.5 * (first + last) * fine.resolution_mm;
}

double CoarseMap::ColClockRad(int col) const {
  const int first = FineCol(col), last = std::min(fine.cols, first + factor);
  return 0.5 * (first + last) * 2.0 * std::numbers::pi / fine.cols;
}

double CoarseMap::ColArcMm(double radius_mm) const {
  return factor * 2.0 * std::numbers::pi * radius_mm / fine.cols;
}

CoarseMapBuilder::CoarseMapBuilder(const MapGrid& fine, double cell_mm) {
  SEWER3D_CHECK(fine.rows > 0 && fine.cols > 0 && fine.resolution_mm > 0.0 && cell_mm > 0.0);
  map_.fine = fine;
  map_.factor = std::max(1, static_cast<int>(std::lround(cell_mm / fine.resolution_mm)));
  const int rows = (fine.rows + map_.factor - 1) / map_.factor;
  const int cols = (fine.cols + map_.factor - 1) / map_.factor;
  sum_ = cv::Mat1d::zeros(rows, cols);
  count_ = cv::Mat1i::zeros(rows, cols);
}

void CoarseMapBuilder::Add(const PipeMaps& tile) {
  const MapGrid& g = map_.fine;
  SEWER3D_CHECK(tile.grid.cols == g.cols && tile.displacement_mm.rows == tile.grid.rows);
  const int first_row =
      static_cast<int>(std::lround((tile.grid.station0_mm - g.station0_mm) / g.resolution_mm));
  SEWER3D_CHECK(first_row >= 0 && first_row + tile.grid.rows <= g.rows);
  const int f = map_.factor;
  for (int r = 0; r < tile.grid.rows; ++r) {
    const float* d = tile.displacement_mm.ptr<float>(r);
    double* sum = sum_.ptr<double>((first_row + r) / f);
    int* count = count_.ptr<int>((first_row + r) / f);
    for (int c = 0; c < g.cols; ++c) {
      if (!std::isfinite(d[c])) continue;
      sum[c / f] += d[c];
      ++count[c / f];
    }
  }
}

CoarseMap CoarseMapBuilder::Finish() const {
  CoarseMap out = map_;
  const int f = map_.factor;
  out.displacement_mm.create(sum_.rows, sum_.cols);
  out.measured.create(sum_.rows, sum_.cols);
  for (int r = 0; r < sum_.rows; ++r) {
    const int rows = std::min(map_.fine.rows, (r + 1) * f) - r * f;
    for (int c = 0; c < sum_.cols; ++c) {
      const int cols = std::min(map_.fine.cols, (c + 1) * f) - c * f;
      const int n = count_(r, c);
      out.measured(r, c) = static_cast<float>(n) / static_cast<float>(rows * cols);
      out.displacement_mm(r, c) = 2 * n >= rows * cols && n > 0
                                      ? static_cast<float>(sum_(r, c) / n)
                                      : std::numeric_limits<float>::quiet_NaN();
    }
  }
  return out;
}

}  // namespace sewer3d
