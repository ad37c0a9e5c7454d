#include "sewer3d/decode/niblack.hpp"

#include <cmath>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

void NiblackOptions::Check() const {
  SEWER3D_CHECK(window >= 3 && window % 2 == 1, "window " << window << " must be odd and >= 3");
  SEWER3D_CHECK(std::isfinite(k), "k");
  SEWER3D_CHECK(min_contrast >= 0.0, "min_contrast " << min_contrast);
}

NiblackBinariser::NiblackBinariser(const NiblackOptions& options) : options_(options) {
  options_.Check();
}

void NiblackBinariser::Apply(const cv::Mat& image, cv::Mat1b& mask) {
  SEWER3D_CHECK(image.channels() == 1 && (image.depth() == CV_8U || image.depth() == CV_16U),
                "Niblack needs an 8-bit or 16-bit grey image");
  const int rows = image.rows, cols = image.cols, r = options_.window / 2;
  mask.create(rows, cols);
  mean_.create(rows, cols);
  // Vertical running sums per column over rows [v − r, v + r], updated as v advances; the
  // horizontal sum over those column sums is another running sum along the row.
  column_sum_.assign(cols, 0.0);
  column_sum2_.assign(cols, 0.0);
  auto value = [&](int v, int u) -> double {
    return image.depth() == CV_8U ? image.at<std::uint8_t>(v, u) : image.at<std::uint16_t>(v, u);
  };
  for (int v = 0; v < std::min(r, rows); ++v) {
    for (int u = 0; u < cols; ++u) {
      const double x = value(v, u);
      column_sum_[u] += x;
      column_sum2_[u] += x * x;
    }
  }
  for (int v = 0; v < rows; ++v) {
    const int add = v + r, drop = v - r - 1;
    if (add < rows) {
      for (int u = 0; u < cols; ++u) {
        const double x = value(add, u);
        column_sum_[u] += x;
        column_sum2_[u] += x * x;
      }
    }
    if (drop >= 0) {
      for (int u = 0; u < cols; ++u) {
        const double x = value(drop, u);
        column_sum_[u] -= x;
        column_sum2_[u] -= x * x;
      }
    }
    const int window_rows = std::min(rows - 1, v + r) - std::max(0, v - r) + 1;
    double s = 0.0, s2 = 0.0;
    for (int u = 0; u < std::min(r, cols); ++u) s += column_sum_[u], s2 += column_sum2_[u];
    for (int u = 0; u < cols; ++u) {
      if (u + r < cols) s += column_sum_[u + r], s2 += column_sum2_[u + r];
      if (u - r - 1 >= 0) s -= column_sum_[u - r - 1], s2 -= column_sum2_[u - r - 1];
      const int window_cols = std::min(cols - 1, u + r) - std::max(0, u - r) + 1;
      const double n = double(window_rows) * window_cols;
      const double mean = s / n;
      const double variance = std::max(0.0, s2 / n - mean * mean);
      const double x = value(v, u);
      const double threshold = std::max(mean + options_.k * std::sqrt(variance), mean + options_.min_contrast);
      mask(v, u) = x > threshold ? 255 : 0;
      mean_(v, u) = static_cast<float>(mean);
    }
  }
}

}  // namespace sewer3d
