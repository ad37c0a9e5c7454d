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
  double level = 0.4;                          // ring light power × exposure
  cv::Vec3d emission_exponent{2.0, 1.5, 1.1};  // cos^k of the emission angle: warmer outside
  cv::Vec3d vignetting{0.30, 0.35, 0.42};      // 1 - a r², r = radius / half diagonal

  cv::Mat3f Light(const cv::Mat2f& normalised) const {
    cv::Mat3f out(normalised.size());
    const double half_diag = 0.5 * std::hypot(out.cols, out.rows);
    for (int r = 0; r < out.rows; ++r) {
      for (int c = 0; c < out.cols; ++c) {
        const cv::Vec2f& xy = normalised(r, c);
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
  const double radius = 150.0 + 10.0 * u(rng), x0 = 20.0 * u(rng), z0 = -35.0 + 15.0 * u(rng);
  const cv::Vec3d n = cv::normalize(cv::Vec3d(0.4 * u(rng), 0.4 * u(rng), 1.0));
  const double h = 120.0 + 20.0 * u(rng);
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

// Smooth random field with unit standard deviation and correlation length ~sigma_px: white
// noise on a grid of sigma_px spacing, interpolated bicubically.
cv::Mat1f SmoothNoise(cv::Size size, double sigma_px, std::mt19937& rng) {
  cv::Mat1f coarse(static_cast<int>(size.height / sigma_px) + 4,
                   static_cast<int>(size.width / sigma_px) + 4);
  cv::RNG cv_rng(rng());
  cv_rng.fill(coarse, cv::RNG::NORMAL, 0.0, 1.0);
  cv::Mat1f fine;
  cv::resize(coarse, fine, cv::Size(), sigma_px, sigma_px, cv::INTER_CUBIC);
  fine = fine(cv::Rect(cv::Point(static_cast<int>(2 * sigma_px), static_cast<int>(2 * sigma_px)),
                       size))
             .clone();
  cv::Scalar mean, stddev;
  cv::meanStdDev(fine, mean, stddev);
  return (fine - mean[0]) / stddev[0];
}

// Warm grey concrete with smooth lightness (σ 0.25 in ln) and chroma (σ 0.08) variations and
// per-pixel speckle (σ 0.12).
cv::Mat3f RandomAlbedo(cv::Size size, std::mt19937& rng) {
  const cv::Vec3d base(0.30, 0.36, 0.42);
  const cv::Mat1f common = SmoothNoise(size, 12.0, rng);
  const cv::Mat1f chroma[3] = {SmoothNoise(size, 25.0, rng), SmoothNoise(size, 25.0, rng),
                               SmoothNoise(size, 25.0, rng)};
  cv::Mat1f speckle(size);
  cv::RNG cv_rng(rng());
  cv_rng.fill(speckle, cv::RNG::NORMAL, 0.0, 0.12);
  cv::Mat3f out(size);
  for (int r = 0; r < size.height; ++r) {
    for (int c = 0; c < size.width; ++c) {
      const float s = speckle(r, c);
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
  constexpr double kFullWell = 10000.0, kReadNoise = 3.0;
  cv::Mat3f n(albedo.size()), out(albedo.size());
  cv::RNG cv_rng(rng());
  cv_rng.fill(n, cv::RNG::NORMAL, 0.0, 1.0);
  for (int r = 0; r < out.rows; ++r) {
    for (int c = 0; c < out.cols; ++c) {
      for (int k = 0; k < 3; ++k) {
        const double e = kFullWell * albedo(r, c)[k] * light(r, c)[k] * g(r, c);
        out(r, c)[k] = static_cast<float>(
            (e + std::sqrt(e + kReadNoise * kReadNoise) * n(r, c)[k]) / kFullWell);
      }
    }
  }
  return LinearFromSrgb8(Srgb8FromLinear(out));
}

// The camera: the default module at 320 x 240 (the statistics per grid cell of 20 px match
// the full-size module's 64 x 48 grid of 40 px cells up to the albedo's correlation length).
const CameraModel& Camera() {
  static const CameraModel camera(testing::SmallDefaultModule(320).camera);
  return camera;
}

ReferenceLightOptions Options() {
  ReferenceLightOptions options;
  options.grid_cols = 16;
  options.grid_rows = 12;
  options.geometry.reference_distance_mm = kRefDistanceMm;
  return options;
}

// Median albedo of RandomAlbedo (the reference's factor per channel).
const cv::Vec3d kMedianAlbedo(0.30, 0.36, 0.42);

// Module B: opposite white-balance error, brighter light, other vignetting.
SyntheticModule ModuleB() {
  SyntheticModule b;
  b.white_balance = cv::Vec3d(0.85, 1.0, 1.2);
  b.level = 0.55;
  b.vignetting = cv::Vec3d(0.38, 0.33, 0.30);
  return b;
}

struct Estimated {
  ReferenceLightResult result;
  std::size_t memory_after_first = 0, memory_after_last = 0;
};

// Feeds `frames` random walls (every third a plane, every fourth with a hole in the depth).
Estimated Estimate(const SyntheticModule& module, int frames, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const cv::Mat2f normalised = NormalisedCoordinates(Camera());
  const cv::Mat3f light = module.Light(normalised);
  ReferenceLightEstimator estimator(Camera(), Options());
  Estimated out;
  for (int i = 0; i < frames; ++i) {
    Wall wall = MakeWall(normalised, rng, i % 3 == 0);
    const cv::Mat3f observed = Observe(RandomAlbedo(light.size(), rng), light, wall.g, rng);
    if (i % 4 == 1) cv::circle(wall.depth_mm, {160, 120}, 40, cv::Scalar(NAN), cv::FILLED);
    estimator.Add(observed, wall.depth_mm);
    if (i == 0) out.memory_after_first = estimator.memory_bytes();
  }
  out.memory_after_last = estimator.memory_bytes();
  out.result = estimator.Estimate();
  return out;
}

constexpr int kFrames = 32;

class ShadingTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    a_ = new Estimated(Estimate(SyntheticModule(), kFrames, 101));
    b_ = new Estimated(Estimate(ModuleB(), kFrames, 202));
  }
  static void TearDownTestSuite() {
    delete a_;
    delete b_;
  }
  ShadingTest() : normalised_(NormalisedCoordinates(Camera())) {}

  static Estimated* a_;
  static Estimated* b_;
  cv::Mat2f normalised_;
};
Estimated* ShadingTest::a_ = nullptr;
Estimated* ShadingTest::b_ = nullptr;

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

// Expected error of the reference (log): the per-cell median of log albedo (σ ≈ 0.29, of
// which 0.25 correlated over ~12 px, so ~3 independent draws per 20 px cell and frame) has
// σ ≈ 1.25 · 0.29 / √(3 · 32) ≈ 0.037; the 7-cell quadratic fit keeps 0.33 of it inside the
// grid (≈ 0.012 rms) but 0.76 at the corners, where the fit is evaluated at its window's end
// and extrapolated half a cell further (σ ≈ 0.03-0.04; single corner pixels reach 0.12).
// Bounds: rms 0.025 (2x), 99th percentile 0.08 (the border cells, ~2.5σ).
TEST_F(ShadingTest, ReferenceRecoversTheLightUpToTheMedianAlbedo) {
  for (const auto& [module, estimated] :
       {std::pair(SyntheticModule(), a_), std::pair(ModuleB(), b_)}) {
    const ReferenceLightResult& result = estimated->result;
    ASSERT_TRUE(result.reference);
    EXPECT_EQ(result.report.frames, kFrames);
    EXPECT_EQ(result.report.cells_filled, 0);
    EXPECT_GT(result.report.pixels_without_geometry, 0);  // the holes
    const cv::Mat3f estimate = result.reference->Render();
    const cv::Mat3f truth = module.Light(normalised_);
    for (int k = 0; k < 3; ++k) {
      std::vector<double> log_ratio;
      for (int r = 0; r < truth.rows; ++r) {
        for (int c = 0; c < truth.cols; ++c)
          log_ratio.push_back(std::log(estimate(r, c)[k] / truth(r, c)[k]));
      }
      std::vector<double> sorted = log_ratio;
      std::sort(sorted.begin(), sorted.end());
      const double factor = std::exp(sorted[sorted.size() / 2]);
      std::vector<double> error;
      double sum2 = 0.0;
      for (double v : log_ratio) {
        error.push_back(std::abs(v - std::log(factor)));
        sum2 += error.back() * error.back();
      }
      std::sort(error.begin(), error.end());
      const double rms = std::sqrt(sum2 / static_cast<double>(error.size()));
      const double p99 = error[error.size() * 99 / 100];
      // The factor is the median albedo (its median speckle is 1); 3 % covers the estimate.
      EXPECT_NEAR(factor / kMedianAlbedo[k], 1.0, 0.03) << "channel " << k;
      EXPECT_LT(rms, 0.025) << "channel " << k;
      EXPECT_LT(p99, 0.08) << "channel " << k;
      std::printf("channel %d: factor %.4f (median albedo %.2f), rms %.4f, p99 %.4f, max %.4f\n", k,
                  factor, kMedianAlbedo[k], rms, p99, error.back());
    }
  }
}

// One test wall seen by a module with its estimated reference, and the truth.
struct TestView {
  cv::Mat3f albedo, observed;
  Wall wall;
};
TestView View(const SyntheticModule& module, const cv::Mat2f& normalised, std::uint32_t seed) {
  std::mt19937 rng(seed);
  TestView v;
  v.wall = MakeWall(normalised, rng, false);
  v.albedo = RandomAlbedo(normalised.size(), rng);
  v.observed = Observe(v.albedo, module.Light(normalised), v.wall.g, rng);
  return v;
}

// Acceptance metric (mean ΔE00 against the albedo after one global gain per channel). Floor:
// the same observation divided by the true L · G, i.e. sensor noise and 8-bit quantisation
// alone (≈ 1.7 here). The estimated reference adds its ~1.5 % rms error: bound floor + 1.
TEST_F(ShadingTest, CorrectionBringsTheTextureToTheAlbedoAfterOneGlobalGain) {
  const SyntheticModule module;
  const TestView view = View(module, normalised_, 7);
  const cv::Mat3f light = module.Light(normalised_);
  cv::Mat3f ideal(view.observed.size());
  for (int r = 0; r < ideal.rows; ++r) {
    for (int c = 0; c < ideal.cols; ++c) {
      for (int k = 0; k < 3; ++k) {
        ideal(r, c)[k] = view.observed(r, c)[k] / (light(r, c)[k] * view.wall.g(r, c));
      }
    }
  }
  const double floor = CompareAfterGlobalGain(ideal, view.albedo).delta_e.mean;
  const double uncorrected = CompareAfterGlobalGain(view.observed, view.albedo).delta_e.mean;
  for (CorrectionSpace space : {CorrectionSpace::kLab, CorrectionSpace::kLinear}) {
    CorrectionOptions options;
    options.space = space;
    const ShadingCorrector corrector(Camera(), *a_->result.reference, options);
    const CorrectedTexture corrected = corrector.Correct(view.observed, view.wall.depth_mm);
    EXPECT_EQ(corrected.report.pixels_corrected, ideal.rows * ideal.cols);
    const GainedDeltaE result =
        CompareAfterGlobalGain(corrected.linear_bgr, view.albedo, corrected.full_mask);
    const char* name = space == CorrectionSpace::kLab ? "Lab" : "linear";
    std::printf("%s: mean ΔE00 %.2f (median %.2f, p95 %.2f); uncorrected %.2f; floor %.2f\n", name,
                result.delta_e.mean, result.delta_e.median, result.delta_e.p95, uncorrected, floor);
    EXPECT_LT(result.delta_e.mean, 3.0) << name;
    EXPECT_LT(result.delta_e.mean, floor + 1.0) << name;
    EXPECT_LT(3.0 * result.delta_e.mean, uncorrected) << name;
    // The run's median wall becomes the neutral grey of the chosen level: the gain that
    // brings the corrected texture back to the albedo is the median albedo over that level.
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(result.gains_bgr[k] * options.wall_level_linear / kMedianAlbedo[k], 1.0, 0.05);
    }
  }
}

// Noise-free, with the true light as the reference (one grid cell per pixel): the linear
// correction is exact up to G from finite differences (< 5e-3); the Lab one adds the error of
// removing a cast as an a*/b* offset, which grows with the albedo's chroma and the cast.
TEST_F(ShadingTest, CorrectionWithTheTrueLightIsExactInLinearAndCloseInLab) {
  const SyntheticModule module;
  std::mt19937 rng(13);
  const Wall wall = MakeWall(normalised_, rng, false);
  const cv::Mat3f albedo = RandomAlbedo(normalised_.size(), rng);
  const cv::Mat3f light = module.Light(normalised_);
  ReferenceLight reference;
  reference.image_size = light.size();
  reference.grid_cols = light.cols;
  reference.grid_rows = light.rows;
  reference.geometry.reference_distance_mm = kRefDistanceMm;
  cv::Mat3f observed(light.size());
  for (int r = 0; r < light.rows; ++r) {
    for (int c = 0; c < light.cols; ++c) {
      const cv::Vec3f& l = light(r, c);
      reference.log2_bgr.emplace_back(std::log2(l[0]), std::log2(l[1]), std::log2(l[2]));
      observed(r, c) = albedo(r, c).mul(l) * wall.g(r, c);
    }
  }
  for (CorrectionSpace space : {CorrectionSpace::kLinear, CorrectionSpace::kLab}) {
    CorrectionOptions options;
    options.space = space;
    const CorrectedTexture corrected =
        ShadingCorrector(Camera(), reference, options).Correct(observed, wall.depth_mm);
    const GainedDeltaE result = CompareAfterGlobalGain(corrected.linear_bgr, albedo);
    std::printf("%s, true light, no noise: mean ΔE00 %.3f, p95 %.3f\n",
                space == CorrectionSpace::kLab ? "Lab" : "linear", result.delta_e.mean,
                result.delta_e.p95);
    EXPECT_LT(result.delta_e.mean, space == CorrectionSpace::kLab ? 1.0 : 0.05);
  }
}

// Mean ΔE00 of 8 x 8 px block means: the colour the two modules give the wall, without the
// independent sensor noise of their two observations.
double BlockDeltaE(const cv::Mat3f& a, const cv::Mat3f& b) {
  cv::Mat3f small_a, small_b;
  cv::resize(a, small_a, a.size() / 8, 0, 0, cv::INTER_AREA);
  cv::resize(b, small_b, b.size() / 8, 0, 0, cv::INTER_AREA);
  return CompareDeltaE2000(small_a, small_b).mean;
}

// Same-median-wall assumption (docs/texture.md): both modules saw walls of the same median
// albedo, so both map it to the same grey and the same wall gets the same corrected colour
// despite opposite white-balance errors and 1.4x different light.
TEST_F(ShadingTest, ModulesWithDifferentCastsAgreeOnTheSameWall) {
  const TestView view_a = View(SyntheticModule(), normalised_, 9);
  const TestView view_b = View(ModuleB(), normalised_, 9);  // same wall and albedo
  ASSERT_EQ(cv::norm(view_a.albedo, view_b.albedo, cv::NORM_INF), 0.0);
  const double uncorrected = BlockDeltaE(view_a.observed, view_b.observed);
  for (CorrectionSpace space : {CorrectionSpace::kLab, CorrectionSpace::kLinear}) {
    CorrectionOptions options;
    options.space = space;
    const CorrectedTexture a = ShadingCorrector(Camera(), *a_->result.reference, options)
                                   .Correct(view_a.observed, view_a.wall.depth_mm);
    const CorrectedTexture b = ShadingCorrector(Camera(), *b_->result.reference, options)
                                   .Correct(view_b.observed, view_b.wall.depth_mm);
    const double blocks = BlockDeltaE(a.linear_bgr, b.linear_bgr);
    const double pixels = CompareDeltaE2000(a.linear_bgr, b.linear_bgr).mean;
    std::printf("%s: modules differ by ΔE00 %.2f (8x8 blocks), %.2f (pixels); uncorrected %.2f\n",
                space == CorrectionSpace::kLab ? "Lab" : "linear", blocks, pixels, uncorrected);
    EXPECT_LT(blocks, 2.0);
    EXPECT_GT(uncorrected, 5.0 * blocks);
  }
}

TEST_F(ShadingTest, MemoryDoesNotGrowWithFrames) {
  EXPECT_EQ(a_->memory_after_first, a_->memory_after_last);
  const ReferenceLightOptions o = Options();
  const std::size_t histograms = static_cast<std::size_t>(o.grid_cols) * o.grid_rows * 3 *
                                 ((o.log2_max - o.log2_min) * o.bins_per_stop + 2) * 4;
  EXPECT_EQ(a_->memory_after_last, histograms + 320 * 240 * sizeof(cv::Vec2f));
}

// The default 64 x 48 grid on a 320 x 240 camera would give a cell 25 pixels of a frame, under
// min_samples_per_cell (100): a run of one acquisition per module had no reference at all. The
// grid shrinks to 10 px cells (32 x 24), so one frame fills every cell.
TEST_F(ShadingTest, OneFrameOfASmallCameraFillsEveryCell) {
  std::mt19937 rng(5);
  ReferenceLightOptions options;
  options.geometry.reference_distance_mm = kRefDistanceMm;
  ReferenceLightEstimator estimator(Camera(), options);
  const Wall wall = MakeWall(normalised_, rng, false);
  estimator.Add(
      Observe(RandomAlbedo(wall.g.size(), rng), SyntheticModule().Light(normalised_), wall.g, rng),
      wall.depth_mm);
  const ReferenceLightResult result = estimator.Estimate();
  ASSERT_TRUE(result.reference);
  EXPECT_EQ(result.reference->grid_cols, 32);
  EXPECT_EQ(result.reference->grid_rows, 24);
  EXPECT_EQ(result.report.cells, 32 * 24 * 3);
  EXPECT_EQ(result.report.cells_filled, 0);
}

TEST_F(ShadingTest, PixelsWithoutDepthGetTheReferenceOnlyAndAreMarked) {
  TestView view = View(SyntheticModule(), normalised_, 11);
  view.wall.depth_mm(cv::Rect(0, 0, 40, 30)).setTo(NAN);
  const ShadingCorrector corrector(Camera(), *a_->result.reference, CorrectionOptions());
  const CorrectedTexture corrected = corrector.Correct(view.observed, view.wall.depth_mm);
  EXPECT_EQ(corrected.report.pixels_without_depth, 40 * 30);
  EXPECT_EQ(corrected.report.pixels_corrected, 320 * 240 - 40 * 30);
  EXPECT_EQ(cv::countNonZero(corrected.full_mask), 320 * 240 - 40 * 30);
  EXPECT_EQ(corrected.full_mask(10, 10), 0);
  const cv::Vec3f v = corrected.linear_bgr(10, 10);
  EXPECT_TRUE(std::isfinite(v[0] + v[1] + v[2]));
  // The 8-bit path is decode, correct, encode.
  const cv::Mat3b srgb = Srgb8FromLinear(view.observed);
  EXPECT_EQ(cv::norm(corrector.CorrectSrgb8(srgb, view.wall.depth_mm),
                     Srgb8FromLinear(
                         corrector.Correct(LinearFromSrgb8(srgb), view.wall.depth_mm).linear_bgr),
                     cv::NORM_INF),
            0.0);
}

TEST_F(ShadingTest, RejectsBadOptionsAndSizes) {
  ReferenceLightOptions o = Options();
  o.grid_cols = 0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = Options();
  o.saturated_linear = o.dark_linear;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = Options();
  o.geometry.min_cos_incidence = 0.0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  CorrectionOptions c;
  c.wall_level_linear = 0.0;
  EXPECT_THROW(c.Check(), std::invalid_argument);
  ReferenceLightEstimator estimator(Camera(), Options());
  EXPECT_THROW(estimator.Add(cv::Mat3f(10, 10), cv::Mat1f(10, 10)), std::invalid_argument);
  EXPECT_FALSE(estimator.Estimate().reference);  // no frame yet
}

}  // namespace
}  // namespace sewer3d
