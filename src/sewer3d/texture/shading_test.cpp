// Shading and colour correction on synthetic frames: an analytic light field L_m (ring-light
// emission falling off and warming with the emission angle, per-channel vignetting, white
// balance and level per module) times G = cos(incidence) (d_ref / d)² of a pipe wall or a
// plane, times a random smooth + speckled albedo, with shot and read noise and 8-bit sRGB
// quantisation. The estimator must recover L_m up to one factor per channel, the correction
// must bring the texture to the albedo (ΔE00 after one global gain), and two modules with
// different casts and levels must agree on the same wall.

#include "sewer3d/texture/shading.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "sewer3d/testing/small_module.hpp"
#include "sewer3d/texture/colour.hpp"

namespace sewer3d {
namespace {

constexpr double kRefDistanceMm = 150.0;

// What is fixed in the image of one module (BGR throughout).
struct SyntheticModule {
  cv::Vec3d white_balance{1.25, 1.0, 0.8};     // camera white-balance error
  double level = 0.15;                         // ring light power × exposure
  cv::Vec3d emission_exponent{2.0, 1.5, 1.1};  // cos^k of the emission angle: warmer outside
  cv::Vec3d vignetting{0.30, 0.35, 0.42};      // 1 - a r², r = radius / half diagonal

  cv::Mat3f Light(const cv::Mat2f& normalised) const {
    cv::Mat3f out(normalised.size());
    const double half_diag = 0.5 * std::hypot(out.cols, out.rows);
    for (int r = 0; r < out.rows; ++r) {
      for (int c = 0; c < out.cols; ++c) {
        const cv::Vec2f xy = normalised(r, c);
        const double cos_theta = 1.0 / std::sqrt(1.0 + xy.dot(xy));
        const double rho2 =
            std::pow(std::hypot(c - 0.5 * out.cols, r - 0.5 * out.rows) / half_diag, 2);
        for (int k = 0; k < 3; ++k) {
          out(r, c)[k] = static_cast<float>(level * white_balance[k] *
                                            std::pow(cos_theta, emission_exponent[k]) *
                                            (1.0 - vignetting[k] * rho2));
        }
      }
    }
    return out;
  }
};

// A wall seen by the camera: depth and the true G, analytic.
struct Wall {
  cv::Mat1f depth_mm, g;
};

// Pipe of radius R, axis parallel to camera y through (x0, ·, z0) (camera inside, z0 < 0),
// or (plane = true) the plane n · X = h.
Wall MakeWall(const cv::Mat2f& normalised, std::mt19937& rng, bool plane) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double radius = 150.0 + 50.0 * u(rng), x0 = 20.0 * u(rng), z0 = -35.0 + 15.0 * u(rng);
  const cv::Vec3d n = cv::normalize(cv::Vec3d(0.4 * u(rng), 0.4 * u(rng), 1.0));
  const double h = 110.0 + 30.0 * u(rng);
  Wall wall{cv::Mat1f(normalised.size()), cv::Mat1f(normalised.size())};
  for (int r = 0; r < normalised.rows; ++r) {
    for (int c = 0; c < normalised.cols; ++c) {
      const cv::Vec3d ray(normalised(r, c)[0], normalised(r, c)[1], 1.0);
      double z = 0.0;
      cv::Vec3d normal = n;
      if (plane) {
        z = h / n.dot(ray);
      } else {
        const double a = ray[0] * ray[0] + 1.0, b = ray[0] * x0 + z0;
        z = (b + std::sqrt(b * b - a * (x0 * x0 + z0 * z0 - radius * radius))) / a;
        normal = cv::normalize(cv::Vec3d(z * ray[0] - x0, 0.0, z - z0));
      }
      const cv::Vec3d p = z * ray;
      wall.depth_mm(r, c) = static_cast<float>(z);
      wall.g(r, c) = static_cast<float>(std::abs(normal.dot(p)) / cv::norm(p) * kRefDistanceMm *
                                        kRefDistanceMm / p.dot(p));
    }
  }
  return wall;
}

// Gaussian-blurred white noise with unit standard deviation.
cv::Mat1f SmoothNoise(cv::Size size, double sigma_px, std::mt19937& rng) {
  cv::Mat1f noise(size);
  std::normal_distribution<float> n(0.0f, 1.0f);
  for (auto& v : noise) v = n(rng);
  cv::GaussianBlur(noise, noise, cv::Size(), sigma_px);
  cv::Scalar mean, stddev;
  cv::meanStdDev(noise, mean, stddev);
  return (noise - mean[0]) / stddev[0];
}

// Warm grey concrete with smooth lightness (σ 0.25 in ln) and chroma (σ 0.08) variations and
// per-pixel speckle (σ 0.12).
cv::Mat3f RandomAlbedo(cv::Size size, std::mt19937& rng) {
  const cv::Vec3d base(0.30, 0.36, 0.42);
  const cv::Mat1f common = SmoothNoise(size, 12.0, rng);
  const cv::Mat1f chroma[3] = {SmoothNoise(size, 25.0, rng), SmoothNoise(size, 25.0, rng),
                               SmoothNoise(size, 25.0, rng)};
  std::normal_distribution<float> speckle(0.0f, 0.12f);
  cv::Mat3f out(size);
  for (int r = 0; r < size.height; ++r) {
    for (int c = 0; c < size.width; ++c) {
      const float s = speckle(rng);
      for (int k = 0; k < 3; ++k) {
        const double a = base[k] * std::exp(0.25 * common(r, c) + 0.08 * chroma[k](r, c) + s);
        out(r, c)[k] = static_cast<float>(std::min(a, 0.95));
      }
    }
  }
  return out;
}

// albedo · L · G with shot noise (6000 e- at full scale), 3 e- read noise, 8-bit sRGB.
cv::Mat3f Observe(const cv::Mat3f& albedo, const cv::Mat3f& light, const cv::Mat1f& g,
                  std::mt19937& rng) {
  constexpr double kFullWell = 6000.0, kReadNoise = 3.0;
  std::normal_distribution<double> n(0.0, 1.0);
  cv::Mat3f out(albedo.size());
  for (int r = 0; r < out.rows; ++r) {
    for (int c = 0; c < out.cols; ++c) {
      for (int k = 0; k < 3; ++k) {
        const double e = kFullWell * albedo(r, c)[k] * light(r, c)[k] * g(r, c);
        out(r, c)[k] =
            static_cast<float>((e + std::sqrt(e + kReadNoise * kReadNoise) * n(rng)) / kFullWell);
      }
    }
  }
  return LinearFromSrgb8(Srgb8FromLinear(out));
}

class ShadingTest : public ::testing::Test {
 protected:
  ShadingTest() : camera_(testing::SmallDefaultModule().camera) {
    normalised_ = NormalisedCoordinates(camera_);
  }
  ReferenceLightOptions Options() const {
    ReferenceLightOptions options;
    options.geometry.reference_distance_mm = kRefDistanceMm;
    return options;
  }
  // Feeds `frames` random walls (every third a plane, some with a hole in the depth).
  ReferenceLightResult Estimate(const SyntheticModule& module, int frames, std::mt19937& rng,
                                std::size_t* memory_first = nullptr,
                                std::size_t* memory_last = nullptr) {
    ReferenceLightEstimator estimator(camera_, Options());
    const cv::Mat3f light = module.Light(normalised_);
    for (int i = 0; i < frames; ++i) {
      Wall wall = MakeWall(normalised_, rng, i % 3 == 0);
      const cv::Mat3f observed = Observe(RandomAlbedo(light.size(), rng), light, wall.g, rng);
      if (i % 4 == 1) cv::circle(wall.depth_mm, {300, 200}, 60, cv::Scalar(NAN), cv::FILLED);
      estimator.Add(observed, wall.depth_mm);
      if (i == 0 && memory_first) *memory_first = estimator.memory_bytes();
    }
    if (memory_last) *memory_last = estimator.memory_bytes();
    return estimator.Estimate();
  }

  CameraModel camera_;
  cv::Mat2f normalised_;
};

TEST_F(ShadingTest, GeometricFactorMatchesTheAnalyticPipeAndPlane) {
  std::mt19937 rng(3);
  GeometryOptions options;
  options.reference_distance_mm = kRefDistanceMm;
  options.min_cos_incidence = 0.01;
  for (bool plane : {false, true}) {
    const Wall wall = MakeWall(normalised_, rng, plane);
    const cv::Mat1f g = GeometricFactor(wall.depth_mm, normalised_, options);
    double worst = 0.0;
    for (int r = 0; r < g.rows; ++r) {
      for (int c = 0; c < g.cols; ++c)
        worst = std::max(worst, std::abs(g(r, c) / wall.g(r, c) - 1.0));
    }
    // Central differences over ±2 px are exact on a plane and err by O((2 px / R)²) on the
    // pipe; float depths add ~1e-5 relative.
    EXPECT_LT(worst, plane ? 2e-3 : 5e-3) << (plane ? "plane" : "pipe");
  }
  cv::Mat1f depth = MakeWall(normalised_, rng, false).depth_mm;
  depth(100, 100) = NAN;
  EXPECT_TRUE(std::isnan(GeometricFactor(depth, normalised_, options)(100, 100)));
  EXPECT_THROW(GeometricFactor(cv::Mat1f(10, 10, 100.0f), normalised_, options),
               std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
