#include "sewer3d/decode/niblack.hpp"

#include <algorithm>
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

namespace {

// Running box sums over the clipped window: column sums over rows [v − r, v + r] are updated
// as v advances; the row sum over those columns is another running sum. Sums of integer
// pixels and their squares stay exact in doubles (< 2^53). The test x > m + max(k s, c) is
// made without a square root: x − m > c and (x − m)² > k² s² (k ≥ 0).
template <typename Pixel>
void Binarise(const cv::Mat& image, int r, double k, double min_contrast, cv::Mat1b& mask,
              cv::Mat1f& mean_out, std::vector<double>& column_sum, std::vector<double>& column_sum2) {
  const int rows = image.rows, cols = image.cols;
  column_sum.assign(cols, 0.0);
  column_sum2.assign(cols, 0.0);
  auto add_row = [&](int v, double sign) {
    const Pixel* row = image.ptr<Pixel>(v);
    for (int u = 0; u < cols; ++u) {
      const double x = row[u];
      column_sum[u] += sign * x;
      column_sum2[u] += sign * x * x;
    }
  };
  for (int v = 0; v < std::min(r, rows); ++v) add_row(v, 1.0);
  std::vector<double> inverse_count_cols(cols);
  for (int u = 0; u < cols; ++u) {
    inverse_count_cols[u] = 1.0 / (std::min(cols - 1, u + r) - std::max(0, u - r) + 1);
  }
  const double k2 = k * k;
  for (int v = 0; v < rows; ++v) {
    if (v + r < rows) add_row(v + r, 1.0);
    if (v - r - 1 >= 0) add_row(v - r - 1, -1.0);
    const double inverse_rows = 1.0 / (std::min(rows - 1, v + r) - std::max(0, v - r) + 1);
    const Pixel* row = image.ptr<Pixel>(v);
    std::uint8_t* out = mask.ptr<std::uint8_t>(v);
    float* mean_row = mean_out.ptr<float>(v);
    double s = 0.0, s2 = 0.0;
    for (int u = 0; u < std::min(r, cols); ++u) s += column_sum[u], s2 += column_sum2[u];
    for (int u = 0; u < cols; ++u) {
      if (u + r < cols) s += column_sum[u + r], s2 += column_sum2[u + r];
      if (u - r - 1 >= 0) s -= column_sum[u - r - 1], s2 -= column_sum2[u - r - 1];
      const double inverse_n = inverse_rows * inverse_count_cols[u];
      const double mean = s * inverse_n;
      const double variance = s2 * inverse_n - mean * mean;
      const double excess = row[u] - mean;
      out[u] = (excess > min_contrast && (k < 0 ? excess > k * std::sqrt(std::max(0.0, variance))
                                                : excess * excess > k2 * variance))
                   ? 255 : 0;
      mean_row[u] = static_cast<float>(mean);
    }
  }
}

}  // namespace

void NiblackBinariser::Apply(const cv::Mat& image, cv::Mat1b& mask) {
  SEWER3D_CHECK(image.channels() == 1 && (image.depth() == CV_8U || image.depth() == CV_16U),
                "Niblack needs an 8-bit or 16-bit grey image");
  mask.create(image.rows, image.cols);
  mean_.create(image.rows, image.cols);
  const int r = options_.window / 2;
  if (image.depth() == CV_8U) {
    Binarise<std::uint8_t>(image, r, options_.k, options_.min_contrast, mask, mean_, column_sum_, column_sum2_);
  } else {
    Binarise<std::uint16_t>(image, r, options_.k, options_.min_contrast, mask, mean_, column_sum_, column_sum2_);
  }
}

}  // namespace sewer3d
