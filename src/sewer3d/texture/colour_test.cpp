// Colour science: CIEDE2000 on the published test pairs, round trips of the sRGB transfer
// function and of linear sRGB ↔ XYZ ↔ L*a*b*, image conversions, ΔE statistics and the
// global-gain fit of the acceptance metric.

#include "sewer3d/texture/colour.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace sewer3d {
namespace {

// Sharma, Wu, Dalal, "The CIEDE2000 color-difference formula: implementation notes,
// supplementary test data, and mathematical observations", Color Res. Appl. 30(1), 2005,
// Table 1: L1, a1, b1, L2, a2, b2, ΔE00 (rounded to 4 decimals).
constexpr std::array<std::array<double, 7>, 34> kSharmaPairs{{
    {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
    {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},
    {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},
    {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
    {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},
    {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
    {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
    {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},
    {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},
    {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},
    {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
    {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630},
    {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},
    {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},
    {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373},
    {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},
    {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},
    {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},
    {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},
    {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},
}};

TEST(Colour, Ciede2000MatchesAllSharmaPairsAndIsSymmetric) {
  for (size_t i = 0; i < kSharmaPairs.size(); ++i) {
    const auto& p = kSharmaPairs[i];
    const Eigen::Vector3d lab1(p[0], p[1], p[2]), lab2(p[3], p[4], p[5]);
    // The table is rounded to 4 decimals: |error| ≤ 0.5e-4 plus float noise.
    EXPECT_NEAR(DeltaE2000(lab1, lab2), p[6], 1e-4) << "pair " << i + 1;
    EXPECT_NEAR(DeltaE2000(lab2, lab1), p[6], 1e-4) << "pair " << i + 1 << " swapped";
  }
  EXPECT_EQ(DeltaE2000({40.0, 10.0, -5.0}, {40.0, 10.0, -5.0}), 0.0);
}

TEST(Colour, SrgbTransferRoundTripAndKnownValues) {
  EXPECT_DOUBLE_EQ(SrgbToLinear(0.0), 0.0);
  EXPECT_NEAR(SrgbToLinear(1.0), 1.0, 1e-12);
  EXPECT_NEAR(SrgbToLinear(0.5), 0.214041, 1e-6);  // IEC 61966-2-1 curve at mid-scale
  EXPECT_NEAR(SrgbToLinear(0.04045), 0.04045 / 12.92, 1e-12);
  // The two pieces meet: continuous at the break point (within 1e-7 of the standard's
  // rounded constants).
  EXPECT_NEAR(SrgbToLinear(0.04045 + 1e-9), SrgbToLinear(0.04045), 1e-7);
  for (double v = 0.0; v <= 1.0; v += 0.001) {
    EXPECT_NEAR(LinearToSrgb(SrgbToLinear(v)), v, 1e-12);
  }
}

TEST(Colour, LabRoundTripsAndReferenceColours) {
  const Eigen::Vector3d white_lab = LinearRgbToLab(Eigen::Vector3d::Ones());
  EXPECT_NEAR(white_lab.x(), 100.0, 1e-9);
  EXPECT_NEAR(white_lab.y(), 0.0, 1e-9);
  EXPECT_NEAR(white_lab.z(), 0.0, 1e-9);
  EXPECT_NEAR(WhiteXyz().x(), 0.95047, 1e-5);  // D65
  EXPECT_NEAR(WhiteXyz().z(), 1.08883, 1e-5);
  // sRGB red (1, 0, 0): L* 53.24, a* 80.09, b* 67.20 (widely tabulated, D65).
  const Eigen::Vector3d red = LinearRgbToLab({1.0, 0.0, 0.0});
  EXPECT_NEAR(red.x(), 53.24, 0.01);
  EXPECT_NEAR(red.y(), 80.09, 0.01);
  EXPECT_NEAR(red.z(), 67.20, 0.01);
  // Mid grey: linear 0.18 has L* 49.50 (Y = 0.18 above the linear segment).
  EXPECT_NEAR(LinearRgbToLab(Eigen::Vector3d::Constant(0.18)).x(), 116.0 * std::cbrt(0.18) - 16.0,
              1e-9);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    // Include very dark colours: they exercise the linear segment of the Lab companding.
    const double scale = i % 4 == 0 ? 0.005 : 1.0;
    const Eigen::Vector3d rgb(scale * u(rng), scale * u(rng), scale * u(rng));
    EXPECT_LT((LabToLinearRgb(LinearRgbToLab(rgb)) - rgb).norm(), 1e-12);
    EXPECT_LT((XyzToLinearRgb(LinearRgbToXyz(rgb)) - rgb).norm(), 1e-12);
  }
}

TEST(Colour, ImageConversionsRoundTripInBgrOrder) {
  cv::Mat3b srgb(8, 32);
  for (int r = 0; r < srgb.rows; ++r) {
    for (int c = 0; c < srgb.cols; ++c) srgb(r, c) = cv::Vec3b(c * 8, r * 32, 255 - c * 8);
  }
  const cv::Mat3f linear = LinearFromSrgb8(srgb);
  EXPECT_NEAR(linear(0, 16)[0], SrgbToLinear(128 / 255.0), 1e-7);
  EXPECT_EQ(cv::norm(Srgb8FromLinear(linear), srgb, cv::NORM_INF), 0.0);
  // Encoding rounds like lround(255 LinearToSrgb(v)) and clips.
  cv::Mat3f ramp(1, 2001);
  for (int c = 0; c < ramp.cols; ++c) ramp(0, c) = cv::Vec3f::all(c / 1000.0f - 0.5f);
  const cv::Mat3b encoded = Srgb8FromLinear(ramp);
  for (int c = 0; c < ramp.cols; ++c) {
    const double v = std::clamp(static_cast<double>(ramp(0, c)[0]), 0.0, 1.0);
    EXPECT_NEAR(encoded(0, c)[1], 255.0 * LinearToSrgb(v), 0.5 + 1e-4) << v;
  }
  const cv::Mat3f lab = LabFromLinear(linear);
  // BGR image, RGB pixel functions: pure red in BGR is (0, 0, 255).
  cv::Mat3f red(1, 1, cv::Vec3f(0.0f, 0.0f, 1.0f));
  EXPECT_NEAR(LabFromLinear(red)(0, 0)[1], 80.09, 0.01);
  EXPECT_LT(cv::norm(LinearFromLab(lab), linear, cv::NORM_INF), 1e-5);
}

TEST(Colour, DeltaEStatisticsAndGlobalGainRecoverAKnownCast) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.05f, 0.8f);
  cv::Mat3f truth(60, 80);
  for (auto& v : truth) v = cv::Vec3f(u(rng), u(rng), u(rng));
  EXPECT_EQ(CompareDeltaE2000(truth, truth).mean, 0.0);
  const cv::Vec3d cast(0.7, 1.1, 1.6);  // exposure and white-balance error, BGR
  const cv::Mat3f cast_image = ApplyChannelGains(truth, cast);
  EXPECT_GT(CompareDeltaE2000(cast_image, truth).mean, 5.0);
  for (GainFit fit : {GainFit::kLeastSquares, GainFit::kMedianRatio}) {
    const GainedDeltaE result = CompareAfterGlobalGain(cast_image, truth, cv::Mat1b(), fit);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(result.gains_bgr[k] * cast[k], 1.0, 1e-5);
    EXPECT_LT(result.delta_e.mean, 1e-3);
    EXPECT_EQ(result.delta_e.pixels, truth.rows * truth.cols);
  }
  // The mask selects pixels; NaN pixels are skipped.
  cv::Mat1b mask(truth.size(), 0);
  mask(cv::Rect(0, 0, 10, 10)).setTo(255);
  cv::Mat3f with_nan = truth.clone();
  with_nan(0, 0) = cv::Vec3f(NAN, 0.0f, 0.0f);
  EXPECT_EQ(CompareDeltaE2000(with_nan, truth, mask).pixels, 99);
  EXPECT_THROW(CompareDeltaE2000(truth, cv::Mat3f(10, 10)), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
