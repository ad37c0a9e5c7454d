#pragma once
/// \file
/// Niblack local thresholding (paper §decode: robust to cracks and contrasted texture):
/// a pixel is foreground when I > m + k·s, m and s the mean and standard deviation over a
/// w × w window. Box sums by running sums (O(1) per pixel, independent of w); the buffers live
/// in the binariser and are reused from frame to frame.

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace sewer3d {

struct NiblackOptions {
  int window = 21;  ///< odd window side, px (about 2.5 spot pitches)
  double k = 0.3;   ///< weight of the local standard deviation
  /// Foreground also needs I − m ≥ min_contrast (8-bit grey levels; scaled to the image's
  /// bit depth, see LevelScale), which keeps flat dark background (where s is only noise) from
  /// turning into speckle.
  double min_contrast = 4.0;
  /// Or the 3 x 3 mean of I − m ≥ min_contrast_3x3 (8-bit levels; 0: not used): a faint spot
  /// (a black wall, a dark deposit) a few levels above its background over its whole disk,
  /// where single pixels' noise keeps to a third of that mean's.
  double min_contrast_3x3 = 0.0;
  void Check() const;
};

class NiblackBinariser {
 public:
  explicit NiblackBinariser(const NiblackOptions& options);

  /// Binarises an 8-bit or 16-bit single-channel image into `mask` (0 / 255, same size).
  /// Windows are clipped at the image border.
  void Apply(const cv::Mat& image, cv::Mat1b& mask);

  /// Contrast of the last image over its local mean (valid after Apply), the weights of spot
  /// centroids: round(kExcessScale · max(0, I − m) / LevelScale) in 8-bit levels, saturated at
  /// 65535 (4095 levels, beyond any spot). 2 bytes a pixel instead of a float mean: the spot
  /// stage is limited by memory traffic.
  const cv::Mat1w& excess() const { return excess_; }
  static constexpr float kExcessScale = 16.0f;

  /// Grey levels of `image` per 8-bit level: 1 for 8-bit images; for 16-bit ones 2^(b − 8)
  /// with b the bits its largest value needs (at least 8), so 10-, 12- and full 16-bit
  /// captures decode alike.
  static double LevelScale(const cv::Mat& image);

 private:
  NiblackOptions options_;
  cv::Mat1w excess_;
  std::vector<double> column_sum_, column_sum2_;
  std::vector<std::int32_t> int_sum_,
      int_sum2_;  ///< 8-bit images: exact in 32 bits for windows <= 151
};

}  // namespace sewer3d
