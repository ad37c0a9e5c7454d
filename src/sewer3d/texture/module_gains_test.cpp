// Module gains from seams: the ring solve recovers known gains, and a seam measured between two
// cameras that see one wall finds the ratio of their colours.

#include "sewer3d/texture/module_gains.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "sewer3d/testing/pinhole.hpp"

namespace sewer3d {
namespace {

CameraModel Pinhole(int width, int height) { return testing::PinholeCamera(width, height, 200.0); }

// Six modules in a ring with known gains (Σ log = 0): seams measured with 1 % noise give the
// gains back within the noise (≈ 1 % / √2 per seam over a ring of six).
TEST(ModuleGains, TheRingSolveRecoversTheGains) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<cv::Vec3d> log_truth(6);
  cv::Vec3d mean(0, 0, 0);
  for (auto& g : log_truth) {
    for (int c = 0; c < 3; ++c) g[c] = 0.2 * std::uniform_real_distribution<double>(-1, 1)(random);
    mean += g / 6.0;
  }
  for (auto& g : log_truth) g -= mean;
  std::vector<SeamMeasurement> seams;
  for (int repeat = 0; repeat < 4; ++repeat) {
    for (int a = 0; a < 6; ++a) {
      const int b = (a + 1) % 6;
      SeamRatio r;
      r.points = 500;
      for (int c = 0; c < 3; ++c)
        r.log_ratio_bgr[c] = log_truth[a][c] - log_truth[b][c] + noise(random);
      seams.push_back({a, b, r});
    }
  }
  const ModuleGains gains = SolveModuleGains(6, seams);
  ASSERT_EQ(gains.gains_bgr.size(), 6u);
  EXPECT_EQ(gains.seams, 24);
  for (int m = 0; m < 6; ++m) {
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(std::log(gains.gains_bgr[m][c]), log_truth[m][c], 0.01) << m << " " << c;
  }
  EXPECT_NEAR(gains.rms_log_residual, 0.01, 0.004);
  // A module no seam reaches keeps gain 1; a bad index is refused.
  const ModuleGains with_lonely = SolveModuleGains(7, seams);
  EXPECT_EQ(with_lonely.gains_bgr[6], cv::Vec3d(1, 1, 1));
  EXPECT_THROW(SolveModuleGains(3, seams), std::invalid_argument);
}

// Two cameras 40 mm apart looking at a plane 150 mm away: b sees the wall a sees, shifted. With
// colour images that are the same wall times 1.25 / 0.8 / 1.0 in a, the ratio is found exactly;
// depth that disagrees (b's map 10 mm off) leaves no common points.
TEST(ModuleGains, ASeamMeasuresTheRatioOfTwoCamerasColours) {
  const CameraModel camera = Pinhole(160, 120);
  cv::Mat1f depth(120, 160, 150.0f);
  const Rigid3d b_from_a(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-40, 0, 0));
  cv::Mat3f b(120, 160), a(120, 160);
  // The wall's colour varies with its x (mm): a linear-light pattern both cameras see.
  for (int v = 0; v < 120; ++v) {
    for (int u = 0; u < 160; ++u) {
      const double x = (u - 79.5) / 200.0 * 150.0;
      const cv::Vec3f wall(0.2f + 0.001f * float(x + 100), 0.3f, 0.25f);
      const double xb =
          x + 40.0;  // b sits 40 mm along a's x: its pixel at x sees the wall at x + 40
      const cv::Vec3f wall_b(0.2f + 0.001f * float(xb + 100), 0.3f, 0.25f);
      a(v, u) = cv::Vec3f(1.25f * wall[0], 0.8f * wall[1], wall[2]);
      b(v, u) = wall_b;
    }
  }
  SeamOptions options;
  options.stride_px = 2;
  const auto ratio = MeasureSeamRatio(a, depth, camera, b, depth, camera, b_from_a, options);
  ASSERT_TRUE(ratio.has_value());
  EXPECT_GT(ratio->points, 1000);
  EXPECT_NEAR(ratio->log_ratio_bgr[0], std::log(1.25), 0.01);
  EXPECT_NEAR(ratio->log_ratio_bgr[1], std::log(0.8), 0.01);
  EXPECT_NEAR(ratio->log_ratio_bgr[2], 0.0, 0.01);
  const cv::Mat1f wrong_depth(120, 160, 160.0f);
  EXPECT_FALSE(MeasureSeamRatio(a, depth, camera, b, wrong_depth, camera, b_from_a, options));
}

}  // namespace
}  // namespace sewer3d
