#include "sewer3d/sim/sensor.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

TEST(Sensor, ColorFilterNamesRoundTrip) {
  for (const ColorFilter f : {ColorFilter::kNone, ColorFilter::kRggb})
    EXPECT_EQ(ParseColorFilter(ColorFilterName(f)), f);
  EXPECT_FALSE(ParseColorFilter("rggb").has_value());
  EXPECT_FALSE(ParseColorFilter("BGGR").has_value());
}

TEST(Sensor, RggbLayoutIsWhatOpenCvCallsBayerBg) {
  // A uniform colour (R, G, B distinct) mosaicked and demosaiced must come back in the right
  // channels. OpenCV names a layout by the 2 × 2 block starting at row 1, column 1, so our
  // RGGB (R at row 0, column 0) is its COLOR_BayerBG2BGR; BayerRG2BGR swaps R and B.
  const cv::Mat3w rgb(8, 10, cv::Vec3w(200, 120, 40));
  const cv::Mat1w raw = MosaicRggb(rgb);
  EXPECT_EQ(raw(0, 0), 200);  // R at row 0, column 0
  EXPECT_EQ(raw(0, 1), 120);
  EXPECT_EQ(raw(1, 0), 120);
  EXPECT_EQ(raw(1, 1), 40);
  cv::Mat3w bgr, swapped;
  cv::cvtColor(raw, bgr, cv::COLOR_BayerBG2BGR);
  cv::cvtColor(raw, swapped, cv::COLOR_BayerRG2BGR);
  for (int v = 2; v < 6; ++v) {
    for (int u = 2; u < 8; ++u) {
      EXPECT_EQ(bgr(v, u), cv::Vec3w(40, 120, 200)) << v << "," << u;
      EXPECT_EQ(swapped(v, u), cv::Vec3w(200, 120, 40)) << v << "," << u;
    }
  }
}

TEST(Sensor, MosaicOfARenderDemosaicsCloseToTheFullColourRender) {
  const ModuleDescription module = testing::SmallDefaultModule(648);
  Scene plane;
  plane.distance_mm = 150.0;
  plane.material = Material::kConcrete;
  RenderOptions options;  // realistic: noise, defocus, shading
  options.images = RenderImages::kTexture;
  options.sensor.color_filter = ColorFilter::kRggb;
  const RenderedFrame frame = RenderFrame(module, DefaultPatternArray(), plane, options);
  ASSERT_EQ(frame.texture_raw.size(), frame.texture.size());
  cv::Mat3w bgr;
  cv::cvtColor(frame.texture_raw, bgr, cv::COLOR_BayerBG2BGR);
  cv::Mat3w rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  // Bilinear demosaicing of a texture with detail at the pixel scale: per-pixel errors of a
  // few DN, no bias. Bounds: mean |error| < 4 DN (the sensor noise alone is ~2 DN), channel
  // means within 0.5 DN.
  const cv::Rect inner(2, 2, rgb.cols - 4, rgb.rows - 4);
  cv::Mat diff;
  cv::absdiff(rgb(inner), frame.texture(inner), diff);
  const cv::Scalar mae = cv::mean(diff);
  const cv::Scalar mean_demosaiced = cv::mean(rgb(inner)),
                   mean_full = cv::mean(frame.texture(inner));
  RecordProperty("mean_abs_error_dn_g", std::to_string(mae[1]));
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(mae[c], 4.0) << c;
    EXPECT_NEAR(mean_demosaiced[c], mean_full[c], 0.5) << c;
  }
}

}  // namespace
}  // namespace sewer3d
