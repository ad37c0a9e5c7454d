#include <gtest/gtest.h>

#include <random>

#include "sewer3d/decode/niblack.hpp"
#include "sewer3d/decode/spots.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/sim/spot_truth.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

// Both arithmetic paths: exact 32-bit sums (8-bit images) and doubles (16-bit images).
template <typename Image>
void CheckAgainstBruteForce(int max_value) {
  std::mt19937 rng(1);
  Image image(37, 53);
  for (auto& x : image) x = static_cast<typename Image::value_type>(rng() % (max_value + 1));
  NiblackOptions options;
  options.window = 7;
  options.k = 0.4;
  options.min_contrast = 2.0;
  NiblackBinariser binariser(options);
  cv::Mat1b mask;
  binariser.Apply(image, mask);
  // Contrast is in 8-bit levels: a 10-bit image's are 4 of its own.
  const double level = NiblackBinariser::LevelScale(image);
  EXPECT_EQ(level, max_value > 255 ? 4.0 : 1.0);
  for (int v = 0; v < image.rows; ++v) {
    for (int u = 0; u < image.cols; ++u) {
      double s = 0, s2 = 0;
      int n = 0;
      for (int y = std::max(0, v - 3); y <= std::min(image.rows - 1, v + 3); ++y) {
        for (int x = std::max(0, u - 3); x <= std::min(image.cols - 1, u + 3); ++x) {
          s += image(y, x);
          s2 += double(image(y, x)) * image(y, x);
          ++n;
        }
      }
      const double mean = s / n, sd = std::sqrt(std::max(0.0, s2 / n - mean * mean));
      const bool expected = image(v, u) > std::max(mean + 0.4 * sd, mean + 2.0 * level);
      ASSERT_EQ(mask(v, u) != 0, expected) << v << "," << u;
      const double excess =
          std::max(0.0, image(v, u) - mean) * NiblackBinariser::kExcessScale / level;
      ASSERT_NEAR(binariser.excess()(v, u), std::min(excess, 65535.0), 0.5 + 1e-3);  // rounded
    }
  }
}

TEST(Niblack, MatchesBruteForceWindowStatistics) {
  CheckAgainstBruteForce<cv::Mat1w>(1023);
  CheckAgainstBruteForce<cv::Mat1b>(255);
}

TEST(Spots, FindsRenderedSpotsWithSubpixelPrecision) {
  const ModuleDescription module = testing::SmallDefaultModule(648);
  const BinaryArray pattern = DefaultPatternArray();
  Scene plane;
  plane.distance_mm = 130.0;
  plane.tilt_deg = 8.0;
  RenderOptions options;  // realistic: noise, defocus, vignetting, concrete texture
  options.sensor.bits = 10;
  const RenderedFrame frame = RenderFrame(module, pattern, plane, options);

  // The binariser's min_contrast is in 8-bit levels, 4 by default, so 16 of this 10-bit image's.
  // Taken in raw levels (4, 0.4 % of full scale), the concrete's grains lit by the ambient light
  // between the spots would pass as ~200 faint spots (contrast 5-9 DN, real spots 40-540 DN).
  NiblackBinariser binariser(NiblackOptions{});
  cv::Mat1b mask;
  binariser.Apply(frame.pattern, mask);
  const std::vector<Spot> spots = DetectSpots(mask, binariser.excess(), SpotOptions{});

  // Expected centres: projector ray through each element centre -> plane -> camera.
  // Spurious detections are judged against every spot the projector lights, cut ones too.
  const std::vector<Eigen::Vector2d> expected_anywhere =
      ProjectedSpotCentres(module, pattern, plane, false);
  std::vector<Eigen::Vector2d> expected;
  for (const auto& px : ProjectedSpotCentres(module, pattern, plane)) {
    if (px.x() > 4 && px.y() > 4 && px.x() < module.camera.width - 5 &&
        px.y() < module.camera.height - 5) {
      expected.push_back(px);
    }
  }
  ASSERT_GT(expected.size(), 500u);
  int found = 0;
  double sum2 = 0.0;
  for (const auto& e : expected) {
    double best = 1e9;
    for (const auto& s : spots) best = std::min(best, (s.centre_px - e).norm());
    if (best < 1.5) {
      ++found;
      sum2 += best * best;
    }
  }
  const double rms = std::sqrt(sum2 / std::max(found, 1));
  RecordProperty("found", found);
  RecordProperty("expected", static_cast<int>(expected.size()));
  RecordProperty("rms_px", std::to_string(rms));
  EXPECT_GT(found, 0.97 * expected.size());
  EXPECT_LT(rms, 0.15);  // 10-bit noise, defocus and texture-modulated spots
  // Spurious detections: interior spots near no projected element.
  int spurious = 0;
  for (const auto& sp : spots) {
    const Eigen::Vector2d& c = sp.centre_px;
    if (c.x() < 5 || c.y() < 5 || c.x() > module.camera.width - 6 ||
        c.y() > module.camera.height - 6)
      continue;
    double best = 1e9;
    for (const auto& e : expected_anywhere) best = std::min(best, (c - e).norm());
    spurious += best > 1.5;
  }
  RecordProperty("spurious", spurious);
  EXPECT_LT(spurious, 0.01 * expected.size());
}

}  // namespace
}  // namespace sewer3d
