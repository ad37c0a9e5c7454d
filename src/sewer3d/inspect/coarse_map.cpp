#include "sewer3d/inspect/coarse_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
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

double CoarseMap::GreyColMm(double radius_mm) const {
  return grey_factor * 2.0 * std::numbers::pi * radius_mm / fine.cols;
}

double CoarseMap::GreyRowStationMm(double row) const {
  return fine.station0_mm + (row + 0.5) * GreyRowMm();
}

double CoarseMap::GreyColClockRad(double col) const {
  return (col + 0.5) * grey_factor * 2.0 * std::numbers::pi / fine.cols;
}

CoarseMapBuilder::CoarseMapBuilder(const MapGrid& fine, double cell_mm, double grey_cell_mm) {
  SEWER3D_CHECK(fine.rows > 0 && fine.cols > 0 && fine.resolution_mm > 0.0 && cell_mm > 0.0);
  map_.fine = fine;
  map_.factor = std::max(1, static_cast<int>(std::lround(cell_mm / fine.resolution_mm)));
  const int rows = (fine.rows + map_.factor - 1) / map_.factor;
  const int cols = (fine.cols + map_.factor - 1) / map_.factor;
  sum_ = cv::Mat1d::zeros(rows, cols);
  count_ = cv::Mat1i::zeros(rows, cols);
  if (grey_cell_mm > 0.0) {
    const int g = std::clamp(static_cast<int>(std::lround(grey_cell_mm / fine.resolution_mm)), 1,
                             kMaxGreyFactor);
    map_.grey_factor = g;
    grey_sum_ = cv::Mat1w::zeros((fine.rows + g - 1) / g, (fine.cols + g - 1) / g);
    grey_count_ = cv::Mat1b::zeros(grey_sum_.size());
  }
}

void CoarseMapBuilder::AddGrey(const PipeMaps& tile, int first_row) {
  const int g = map_.grey_factor;
  for (int r = 0; r < tile.grid.rows; ++r) {
    const cv::Vec3b* t = tile.texture.ptr<cv::Vec3b>(r);
    const unsigned char* cov = tile.coverage.ptr<unsigned char>(r);
    std::uint16_t* sum = grey_sum_.ptr<std::uint16_t>((first_row + r) / g);
    unsigned char* count = grey_count_.ptr<unsigned char>((first_row + r) / g);
    for (int c = 0; c < tile.grid.cols; ++c) {
      if (cov[c] == static_cast<unsigned char>(Coverage::kNone)) continue;
      // ITU-R BT.601 luma of the BGR cell.
      sum[c / g] = static_cast<std::uint16_t>(
          sum[c / g] + std::lround(0.114 * t[c][0] + 0.587 * t[c][1] + 0.299 * t[c][2]));
      ++count[c / g];
    }
  }
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
  const bool textured = !tile.texture.empty() &&
                        tile.texture.size() == tile.displacement_mm.size() &&
                        tile.coverage.size() == tile.displacement_mm.size();
  if (!grey_sum_.empty() && textured) {
    AddGrey(tile, first_row);
    has_grey_ = true;
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
  if (has_grey_) out.grey = GreyMeans();
  return out;
}

cv::Mat1b CoarseMapBuilder::GreyMeans() const {
  const int g = map_.grey_factor;
  cv::Mat1b grey(grey_sum_.size());
  for (int r = 0; r < grey.rows; ++r) {
    const int rows = std::min(map_.fine.rows, (r + 1) * g) - r * g;
    for (int c = 0; c < grey.cols; ++c) {
      const int cols = std::min(map_.fine.cols, (c + 1) * g) - c * g;
      const int n = grey_count_(r, c);
      // 0 marks "no texture": a measured black cell reads 1.
      grey(r, c) = 2 * n >= rows * cols && n > 0
                       ? static_cast<unsigned char>(std::clamp<long>(
                             std::lround(static_cast<double>(grey_sum_(r, c)) / n), 1L, 255L))
                       : 0;
    }
  }
  return grey;
}

}  // namespace sewer3d
