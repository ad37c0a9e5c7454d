#include "sewer3d/decode/niblack.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

void NiblackOptions::Check() const {
  SEWER3D_VALIDATE(window >= 3 && window % 2 == 1, "window",
                   "must be odd and >= 3, got " << window);
  SEWER3D_VALIDATE(std::isfinite(k), "k", "must be finite");
  ValidateNotNegative("min_contrast", min_contrast);
  ValidateNotNegative("min_contrast_3x3", min_contrast_3x3);
}

NiblackBinariser::NiblackBinariser(const NiblackOptions& options) : options_(options) {
  options_.Check();
}

namespace {

// Running box sums over the clipped window: column sums over rows [v − r, v + r] are updated
// as v advances; the row sum over those columns is another running sum. Sums are exact: in
// 32-bit integers for 8-bit images (151² · 255² < 2³¹), in doubles otherwise (< 2⁵³). The
// test x > m + max(k s, c) is made without a division or square root, multiplied through by
// the window's pixel count n: n x − S > n c and (n x − S)² > k² (n S₂ − S²) (k ≥ 0); the
// second only for the few pixels that pass the first.
template <typename Pixel, typename Acc>
void Binarise(const cv::Mat& image, int r, double k, double min_contrast, double min_contrast_3x3,
              float excess_scale, cv::Mat1b& mask, cv::Mat1w& excess_out,
              std::vector<Acc>& column_sum, std::vector<Acc>& column_sum2) {
  const int rows = image.rows, cols = image.cols;
  column_sum.assign(cols, Acc(0));
  column_sum2.assign(cols, Acc(0));
  auto add_row = [&](int v) {
    const Pixel* row = image.ptr<Pixel>(v);
    for (int u = 0; u < cols; ++u) {
      const Acc x = row[u];
      column_sum[u] += x;
      column_sum2[u] += x * x;
    }
  };
  auto replace_row = [&](int v_in, int v_out) {  // one pass: add row v_in, remove row v_out
    const Pixel* in = image.ptr<Pixel>(v_in);
    const Pixel* out = image.ptr<Pixel>(v_out);
    for (int u = 0; u < cols; ++u) {
      const Acc a = in[u], b = out[u];
      column_sum[u] += a - b;
      column_sum2[u] += a * a - b * b;
    }
  };
  auto subtract_row = [&](int v) {
    const Pixel* row = image.ptr<Pixel>(v);
    for (int u = 0; u < cols; ++u) {
      const Acc x = row[u];
      column_sum[u] -= x;
      column_sum2[u] -= x * x;
    }
  };
  for (int v = 0; v < std::min(r, rows); ++v) add_row(v);
  std::vector<int> count_cols(cols);
  std::vector<float> inverse_count_cols(cols);
  std::vector<Acc> threshold_n(cols), window_sum(cols), window_sum2(cols);
  std::vector<float> count_cols_f(cols), threshold_f(cols);
  // Faint spots (2b): running 3-row column sums, like the window's.
  const bool faint = min_contrast_3x3 > 0.0;
  std::vector<Acc> column3(faint ? cols : 0, Acc(0));
  std::vector<float> count3_cols(column3.size()), row3(column3.size());
  for (int u = 0; u < static_cast<int>(column3.size()); ++u)
    count3_cols[u] = static_cast<float>(std::min(cols - 1, u + 1) - std::max(0, u - 1) + 1);
  auto column3_row = [&](int v, int sign) {
    const Pixel* row = image.ptr<Pixel>(v);
    for (int u = 0; u < cols; ++u) column3[u] += sign * static_cast<Acc>(row[u]);
  };
  if (faint && rows > 0) column3_row(0, 1);
  const auto c3 = static_cast<float>(min_contrast_3x3);
  const auto quiet = static_cast<float>(min_contrast * min_contrast);
  for (int u = 0; u < cols; ++u) {
    count_cols[u] = std::min(cols - 1, u + r) - std::max(0, u - r) + 1;
    inverse_count_cols[u] = 1.0f / count_cols[u];
  }
  // n c for the window's pixel count n; for integer sums e > n c ⟺ e > floor(n c), exactly.
  int threshold_rows = -1;
  auto set_thresholds = [&](int count_rows) {
    if (count_rows == threshold_rows) return;
    threshold_rows = count_rows;
    for (int u = 0; u < cols; ++u) {
      const double nc = min_contrast * count_rows * count_cols[u];
      threshold_n[u] =
          std::is_integral_v<Acc> ? static_cast<Acc>(std::floor(nc)) : static_cast<Acc>(nc);
      threshold_f[u] = static_cast<float>(threshold_n[u]);
      count_cols_f[u] = static_cast<float>(count_cols[u]);
    }
  };
  const double k2 = k * k;
  for (int v = 0; v < rows; ++v) {
    if (v + r < rows && v - r - 1 >= 0) {
      replace_row(v + r, v - r - 1);
    } else if (v + r < rows) {
      add_row(v + r);
    } else if (v - r - 1 >= 0) {
      subtract_row(v - r - 1);
    }
    const int count_rows = std::min(rows - 1, v + r) - std::max(0, v - r) + 1;
    const float inverse_rows = 1.0f / count_rows;
    set_thresholds(count_rows);
    const Pixel* row = image.ptr<Pixel>(v);
    std::uint8_t* out = mask.ptr<std::uint8_t>(v);
    std::uint16_t* excess_row = excess_out.ptr<std::uint16_t>(v);
    // 1) Window sums along the row (running sums: sequential, but only adds).
    Acc s = 0, s2 = 0;
    for (int u = 0; u < std::min(r, cols); ++u) s += column_sum[u], s2 += column_sum2[u];
    for (int u = 0; u < cols; ++u) {
      if (u + r < cols) s += column_sum[u + r], s2 += column_sum2[u + r];
      if (u - r - 1 >= 0) s -= column_sum[u - r - 1], s2 -= column_sum2[u - r - 1];
      window_sum[u] = s;
      window_sum2[u] = s2;
    }
    // Faint spots: the 3 x 3 sums B of the row (running 3-row column sums).
    float rows3 = 0.0f;
    if (faint) {
      if (v + 1 < rows) column3_row(v + 1, 1);
      if (v - 2 >= 0) column3_row(v - 2, -1);
      rows3 = static_cast<float>(std::min(rows - 1, v + 1) - std::max(0, v - 1) + 1);
      row3[0] = static_cast<float>(column3[0]) + (cols > 1 ? static_cast<float>(column3[1]) : 0);
      for (int u = 1; u + 1 < cols; ++u)
        row3[u] = static_cast<float>(column3[u - 1] + column3[u] + column3[u + 1]);
      if (cols > 1) row3[cols - 1] = static_cast<float>(column3[cols - 2] + column3[cols - 1]);
    }
    // 2) Contrast test and excess, no dependency between pixels (vectorises).
    // In floats: n x and S stay below 2²⁴ for 8-bit pixels and windows up to 151, so the
    // first test is exact there; 16-bit images take the double path anyway.
    for (int u = 0; u < cols; ++u) {
      const float x = static_cast<float>(row[u]), sum = static_cast<float>(window_sum[u]);
      const float n = static_cast<float>(count_rows) * count_cols_f[u];
      out[u] = n * x - sum > threshold_f[u] ? 255 : 0;  // n (x − m) > n c
      const float excess = (x - sum * inverse_rows * inverse_count_cols[u]) * excess_scale;
      // Round, then clear negative values with the sign mask: no branch on the sign of
      // I − m, which is noise and would be mispredicted half the time.
      // NOLINTNEXTLINE(bugprone-incorrect-roundings): negative values are cleared below
      int rounded = static_cast<int>(excess + 0.5f);
      rounded &= ~(rounded >> 31);
      excess_row[u] = static_cast<std::uint16_t>(std::min(rounded, 65535));
    }
    // 2b) Or a faint spot: the 3 x 3 mean B / b over the local mean S / n by c₃ (n B − b S ≥
    // c₃ b n) where the window is quiet (standard deviation under min_contrast: a dark wall's
    // faint spots, not the rims of bright ones); the pixel itself above the mean (step 3). In
    // floats: n S₂ ≤ n² (255 L)² for L grey levels per 8-bit level, so its rounding error
    // (6·10⁻⁸ of it, 0.004 n² L²) is far below the quiet bound c² n² = 16 n² L².
    if (faint) {
      for (int u = 0; u < cols; ++u) {
        const float n = static_cast<float>(count_rows) * count_cols_f[u];
        const float b = rows3 * count3_cols[u];
        const auto sum = static_cast<float>(window_sum[u]);
        const bool bright = n * row3[u] - b * sum >= c3 * b * n;
        const bool calm = n * static_cast<float>(window_sum2[u]) - sum * sum < quiet * n * n;
        out[u] = bright && calm ? std::uint8_t{255} : out[u];
      }
    }
    // 3) The variance test for the few that passed: n x − S > 0 and (n x − S)² > k² (n S₂ −
    // S²), exact in doubles.
    for (int u = 0; u < cols; ++u) {
      if (!out[u]) continue;
      const double sum = static_cast<double>(window_sum[u]),
                   n = static_cast<double>(count_rows) * count_cols[u];
      const double excess_n = n * row[u] - sum;
      const double variance_n2 = n * static_cast<double>(window_sum2[u]) - sum * sum;
      const bool spot = k < 0 ? excess_n > k * std::sqrt(std::max(0.0, variance_n2))
                              : excess_n > 0.0 && excess_n * excess_n > k2 * variance_n2;
      if (!spot) out[u] = 0;
    }
  }
}

}  // namespace

double NiblackBinariser::LevelScale(const cv::Mat& image) {
  if (image.depth() != CV_16U) return 1.0;
  double max_value = 0.0;
  cv::minMaxLoc(image, nullptr, &max_value);
  const int bits = std::max(8, static_cast<int>(std::ceil(std::log2(max_value + 1.0))));
  return std::ldexp(1.0, bits - 8);
}

void NiblackBinariser::Apply(const cv::Mat& image, cv::Mat1b& mask) {
  SEWER3D_CHECK(image.channels() == 1 && (image.depth() == CV_8U || image.depth() == CV_16U),
                "Niblack needs an 8-bit or 16-bit grey image");
  mask.create(image.rows, image.cols);
  excess_.create(image.rows, image.cols);
  const int r = options_.window / 2;
  // Contrast in 8-bit units whatever the bit depth: a 12-bit image's levels are 16 of an
  // 8-bit one's (its noise too), so min_contrast and the excess scale by 2^(bits − 8).
  const double level = LevelScale(image);
  const double min_contrast = options_.min_contrast * level;
  const double min_contrast_3x3 = options_.min_contrast_3x3 * level;
  const auto excess_scale = static_cast<float>(kExcessScale / level);
  if (image.depth() == CV_8U && options_.window <= 151) {  // 151² · 255² < 2³¹
    Binarise<std::uint8_t, std::int32_t>(image, r, options_.k, min_contrast, min_contrast_3x3,
                                         excess_scale, mask, excess_, int_sum_, int_sum2_);
  } else if (image.depth() == CV_8U) {
    Binarise<std::uint8_t, double>(image, r, options_.k, min_contrast, min_contrast_3x3,
                                   excess_scale, mask, excess_, column_sum_, column_sum2_);
  } else {
    Binarise<std::uint16_t, double>(image, r, options_.k, min_contrast, min_contrast_3x3,
                                    excess_scale, mask, excess_, column_sum_, column_sum2_);
  }
}

}  // namespace sewer3d
