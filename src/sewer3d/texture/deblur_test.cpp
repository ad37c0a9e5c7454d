// Motion deblur on synthetic images with an exactly known box blur: a pinhole camera looking at
// a plane at 150 mm moving along its y axis, so every pixel has the same blur length along the
// image columns. Also the pipe prior's geometry.

#include "sewer3d/texture/deblur.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <random>

#include "sewer3d/testing/pinhole.hpp"

namespace sewer3d {
namespace {

constexpr double kFocalPx = 500.0, kDepthMm = 150.0, kExposureMs = 4.0;

CameraModel Pinhole(int width, int height) {
  return testing::PinholeCamera(width, height, kFocalPx);
}

// Camera velocity (along camera y) giving a blur of `length_px` on the plane.
Eigen::Vector3d VelocityForBlur(double length_px) {
  return {0.0, length_px * kDepthMm / kFocalPx / (kExposureMs * 1e-3), 0.0};
}

// Rows of 0.2 above `edge_row` and 0.8 below: the value of each pixel is the area average of
// the ideal step, blurred by a centred box of `length_px` along v (supersampled 40x).
cv::Mat3f StepImage(cv::Size size, double edge_row, double length_px) {
  constexpr int kSub = 40;
  cv::Mat3f image(size);
  for (int v = 0; v < size.height; ++v) {
    double sum = 0.0;
    for (int i = 0; i < kSub; ++i) {
      const double y = v - 0.5 + (i + 0.5) / kSub;
      for (int j = 0; j < kSub; ++j) {
        const double s = length_px * ((j + 0.5) / kSub - 0.5);
        sum += (y + s < edge_row) ? 0.2 : 0.8;
      }
    }
    const auto value = static_cast<float>(sum / (kSub * kSub));
    for (int u = 0; u < size.width; ++u) image(v, u) = cv::Vec3f(value, value, value);
  }
  return image;
}

void AddNoise(cv::Mat3f& image, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0F, static_cast<float>(sigma));
  for (cv::Vec3f& p : image) {
    for (int c = 0; c < 3; ++c) p[c] += noise(rng);
  }
}

// 10–90 % rise distance (px) of the column-mean profile of channel 0 around a step 0.2 → 0.8.
double EdgeWidth(const cv::Mat3f& image) {
  std::vector<double> profile(image.rows, 0.0);
  for (int v = 0; v < image.rows; ++v) {
    for (int u = 0; u < image.cols; ++u) profile[v] += image(v, u)[0] / image.cols;
  }
  auto crossing = [&](double level) {
    for (int v = 0; v + 1 < image.rows; ++v) {
      if (profile[v] < level && profile[v + 1] >= level) {
        return v + (level - profile[v]) / (profile[v + 1] - profile[v]);
      }
    }
    return std::nan("");
  };
  return crossing(0.2 + 0.9 * 0.6) - crossing(0.2 + 0.1 * 0.6);
}

TEST(Deblur, RestoresAKnownBoxBlurOfAStepWithoutRinging) {
  const cv::Size size(64, 96);
  const cv::Mat1f depth(size, static_cast<float>(kDepthMm));
  const CameraModel camera = Pinhole(size.width, size.height);
  const double sharp_width = EdgeWidth(StepImage(size, 48.3, 0.0));
  for (const double length : {3.0, 5.0, 8.0}) {
    SCOPED_TRACE("blur " + std::to_string(length) + " px");
    cv::Mat3f blurred = StepImage(size, 48.3, length);
    AddNoise(blurred, 0.005, 7);
    const DeblurResult r = Deblur(blurred, depth, camera, VelocityForBlur(length), kExposureMs);
    EXPECT_TRUE(r.report.along_columns);
    EXPECT_NEAR(r.report.off_axis_deg, 0.0, 1e-6);
    EXPECT_NEAR(r.report.min_length_px, length, 1e-3);
    EXPECT_NEAR(r.report.max_length_px, length, 1e-3);
    EXPECT_EQ(r.report.bins, 1);
    const double before = EdgeWidth(blurred), after = EdgeWidth(r.image);
    RecordProperty("width_" + std::to_string(int(length)),
                   std::to_string(before) + " -> " + std::to_string(after));
    // A box of L px widens a step's 10–90 % rise to 0.8 L; restored to within ~1.2 px of sharp.
    EXPECT_NEAR(before, 0.8 * length, 0.4);
    EXPECT_LT(after, sharp_width + 0.3 * length);
    EXPECT_LT(after, 0.65 * before);
    // Overshoot and undershoot beyond the plateaus (step height 0.6) on the column means.
    double lo = 1e9, hi = -1e9;
    for (int v = 8; v < size.height - 8; ++v) {
      const double m = cv::mean(r.image.row(v))[0];
      lo = std::min(lo, m);
      hi = std::max(hi, m);
    }
    EXPECT_LT((hi - 0.8) / 0.6, 0.10);
    EXPECT_LT((0.2 - lo) / 0.6, 0.10);
  }
}

TEST(Deblur, NoiseGainStaysBelowTheStatedFactor) {
  const cv::Size size(128, 256);
  const CameraModel camera = Pinhole(size.width, size.height);
  cv::Mat3f flat(size, cv::Vec3f(0.5F, 0.5F, 0.5F));
  AddNoise(flat, 0.01, 11);
  // With the noise given as negligible K sits at its floor: the gain bound alone limits noise.
  for (const double given_noise : {0.0, 1e-6}) {
    DeblurOptions options;
    options.noise_sigma = given_noise;
    for (const double length : {1.0, 4.0, 12.0}) {
      const DeblurResult r = Deblur(flat, cv::Mat1f(size, static_cast<float>(kDepthMm)), camera,
                                    VelocityForBlur(length), kExposureMs, options);
      cv::Scalar in_mean, in_std, out_mean, out_std;
      cv::meanStdDev(flat, in_mean, in_std);
      cv::meanStdDev(r.image, out_mean, out_std);
      RecordProperty(
          "noise_gain_" + std::to_string(int(length)) + (given_noise > 0 ? "_floor" : ""),
          std::to_string(out_std[0] / in_std[0]));
      EXPECT_NEAR(out_mean[0], in_mean[0], 1e-3);
      EXPECT_LE(out_std[0], options.max_gain * in_std[0]);
      if (given_noise == 0.0) {
        EXPECT_NEAR(r.report.noise_sigma, 0.01, 0.001);  // estimated
      }
    }
  }
}

TEST(Deblur, WithoutMotionOrDepthTheImageIsUnchanged) {
  const cv::Size size(48, 40);
  const CameraModel camera = Pinhole(size.width, size.height);
  cv::Mat3f image = StepImage(size, 20.0, 0.0);
  AddNoise(image, 0.02, 3);
  const cv::Mat1f depth(size, static_cast<float>(kDepthMm));
  const DeblurResult still = Deblur(image, depth, camera, Eigen::Vector3d::Zero(), kExposureMs);
  EXPECT_EQ(cv::norm(still.image, image, cv::NORM_INF), 0.0);
  EXPECT_EQ(still.report.pixels_restored, 0);
  // Blur below min_length_px (0.5) is left alone, and so are pixels without depth.
  const DeblurResult tiny = Deblur(image, depth, camera, VelocityForBlur(0.4), kExposureMs);
  EXPECT_EQ(cv::norm(tiny.image, image, cv::NORM_INF), 0.0);
  const cv::Mat1f none(size, std::numeric_limits<float>::quiet_NaN());
  const DeblurResult empty = Deblur(image, none, camera, VelocityForBlur(5.0), kExposureMs);
  EXPECT_EQ(cv::norm(empty.image, image, cv::NORM_INF), 0.0);
}

TEST(Deblur, TravelAlongRowsIsRestoredAlongRows) {
  const cv::Size size(96, 64);
  const CameraModel camera = Pinhole(size.width, size.height);
  cv::Mat3f step_v = StepImage(cv::Size(size.height, size.width), 48.3, 5.0), blurred;
  cv::transpose(step_v, blurred);
  const Eigen::Vector3d v = VelocityForBlur(5.0);
  const DeblurResult r = Deblur(blurred, cv::Mat1f(size, static_cast<float>(kDepthMm)), camera,
                                Eigen::Vector3d(v.y(), 0.0, 0.0), kExposureMs);
  EXPECT_FALSE(r.report.along_columns);
  cv::Mat3f back;
  cv::transpose(r.image, back);
  EXPECT_LT(EdgeWidth(back), 0.6 * EdgeWidth(step_v));
}

TEST(Deblur, OptionsAreChecked) {
  DeblurOptions o;
  o.max_gain = 0.5;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.bin_px = 0.0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
