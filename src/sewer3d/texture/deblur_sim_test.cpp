// Motion deblur on rendered textures (648 x 486): a DN300 wall 110 mm from the camera painted
// with stripes across the pipe axis (4 mm dark, 4 mm light, never saturating: sharp edges along
// the travel; the albedo is the test's own, the simulator's concrete has few sharp edges). The
// camera moves 1.6 mm along the pipe during the exposure: 400 mm/s for 4 ms, which at this size
// blurs as many pixels (~6.3) as 100 mm/s does at full size. The blurred image is the mean of 16
// still renders spread over the exposure, plus sensor-like noise: the renderer's own motion blur
// ties each sample's instant to its stratum in the pixel (RenderFrame: tau from k, sy from k / n),
// which lengthens the blur by about one pixel (measured: best-fit box 7.1 px for 6.2 px of
// motion), so it is not the physical box this test needs.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/testing/small_module.hpp"
#include "sewer3d/texture/deblur.hpp"

namespace sewer3d {
namespace {

constexpr double kSpeedMmS = 400.0, kExposureMs = 4.0;

class StripedWall final : public Surface {
 public:
  explicit StripedWall(double shift_mm) : shift_(0.0, shift_mm, 0.0) {
    scene_.type = Scene::Type::kCylinder;
    scene_.diameter_mm = 300.0;
    scene_.axis_point_mm = {0.0, 0.0, -40.0};
  }
  std::optional<SurfaceHit> Intersect(const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction) const override {
    auto hit = sewer3d::Intersect(scene_, origin + shift_, direction);
    if (hit) {
      const bool dark = std::fmod(hit->point.y() + 1000.0, 8.0) < 4.0;
      hit->albedo = Eigen::Vector3d::Constant(dark ? 0.1 : 0.35);
      hit->point -= shift_;
    }
    return hit;
  }
  std::uint64_t MaterialSeed() const override { return 1; }

 private:
  Scene scene_;
  Eigen::Vector3d shift_;
};

// Noise-free texture signal (8-bit digital numbers, float) with the camera shifted along y.
RenderedFrame RenderStill(double shift_mm) {
  RenderOptions o;
  o.images = RenderImages::kTexture;
  o.sensor.noise = false;
  o.supersampling = 2;
  RenderedFrame f =
      RenderFrame(testing::SmallDefaultModule(648), BinaryArray(1, 1), StripedWall(shift_mm), o);
  f.texture_signal *= 255.0;
  return f;
}

// Box blur of the camera's travel (centred on the still frame) as the mean of `n` stills.
cv::Mat3f RenderBlurred(double travel_mm, int n) {
  cv::Mat3f sum(RenderStill(0.0).texture_signal.size(), cv::Vec3f());
  for (int i = 0; i < n; ++i) sum += RenderStill(travel_mm * ((i + 0.5) / n - 0.5)).texture_signal;
  return sum / n;
}

// Gaussian noise of an 8-bit sensor at ~half scale (sigma 1.5 DN), seeded.
cv::Mat3f Noisy(const cv::Mat3f& image, unsigned seed) {
  cv::Mat3f noise(image.size());
  cv::theRNG().state = seed;
  cv::randn(noise, cv::Scalar::all(0.0), cv::Scalar::all(1.5));
  return image + noise;
}

struct EdgeStats {
  double median_width_px = 0.0;   ///< 10–90 % rise along the columns
  double median_overshoot = 0.0;  ///< beyond the sharp image's plateaus, fraction of the step
  int edges = 0;
};

// Edges along the columns of the central half of `image` (grey): crossings of the mid level
// between the plateaus of `sharp` (min/max within ±12 px) and the 10 % / 90 % crossings nearest.
EdgeStats Edges(const cv::Mat3f& image, const cv::Mat3f& sharp) {
  cv::Mat1f g, s;
  cv::cvtColor(image, g, cv::COLOR_RGB2GRAY);
  cv::cvtColor(sharp, s, cv::COLOR_RGB2GRAY);
  std::vector<double> widths, overshoots;
  for (int u = g.cols / 4; u < 3 * g.cols / 4; u += 3) {
    for (int v = g.rows / 4; v < 3 * g.rows / 4; ++v) {
      double lo = 1e9, hi = -1e9, out_lo = 1e9, out_hi = -1e9;
      for (int k = v - 12; k <= v + 13; ++k) {
        lo = std::min<double>(lo, s(k, u));
        hi = std::max<double>(hi, s(k, u));
        out_lo = std::min<double>(out_lo, g(k, u));
        out_hi = std::max<double>(out_hi, g(k, u));
      }
      const double mid = 0.5 * (lo + hi), step = hi - lo;
      if (step < 40.0 || !((g(v, u) - mid) * (g(v + 1, u) - mid) < 0.0)) continue;
      const int dir = g(v + 1, u) > g(v, u) ? 1 : -1;
      auto cross = [&](double level) {  // nearest crossing of `level` walking from the edge
        const double target = dir > 0 ? lo + level * step : hi - level * step;
        for (int d = 0; d < 12; ++d) {
          for (const int k : {v - d, v + d}) {
            const double a = g(k, u) - target, b = g(k + 1, u) - target;
            if (a * b <= 0.0 && a != b) return k + a / (a - b);
          }
        }
        return std::nan("");
      };
      const double w = std::abs(cross(0.9) - cross(0.1));
      if (std::isfinite(w)) widths.push_back(w);
      overshoots.push_back(std::max(out_hi - hi, lo - out_lo) / step);
      v += 6;
    }
  }
  auto median = [](std::vector<double> x) {
    std::nth_element(x.begin(), x.begin() + x.size() / 2, x.end());
    return x.empty() ? NAN : x[x.size() / 2];
  };
  return {median(widths), median(overshoots), static_cast<int>(widths.size())};
}

TEST(DeblurRendered, StripeEdgesSharpenWithoutHalos) {
  const RenderedFrame still = RenderStill(0.0);
  const cv::Mat3f sharp = Noisy(still.texture_signal, 1);
  const cv::Mat3f blurred = Noisy(RenderBlurred(kSpeedMmS * kExposureMs * 1e-3, 16), 2);
  const CameraModel camera(testing::SmallDefaultModule(648).camera);
  const DeblurResult r =
      Deblur(blurred, still.truth_depth, camera, Eigen::Vector3d(0.0, kSpeedMmS, 0.0), kExposureMs);
  const EdgeStats s = Edges(sharp, sharp), b = Edges(blurred, sharp), d = Edges(r.image, sharp);
  const double rmse_blurred =
      cv::norm(blurred, sharp, cv::NORM_L2) / std::sqrt(3.0 * sharp.total());
  const double rmse_deblurred =
      cv::norm(r.image, sharp, cv::NORM_L2) / std::sqrt(3.0 * sharp.total());
  RecordProperty("blur_px", std::to_string(r.report.min_length_px) + ".." +
                                std::to_string(r.report.max_length_px));
  RecordProperty("bins", r.report.bins);
  RecordProperty("time_ms", std::to_string(r.report.time_ms));
  RecordProperty("noise_dn_K", std::to_string(r.report.noise_sigma) + " " +
                                   std::to_string(r.report.noise_to_signal));
  RecordProperty("width_sharp_blurred_deblurred", std::to_string(s.median_width_px) + " " +
                                                      std::to_string(b.median_width_px) + " " +
                                                      std::to_string(d.median_width_px));
  RecordProperty("overshoot_sharp_blurred_deblurred", std::to_string(s.median_overshoot) + " " +
                                                          std::to_string(b.median_overshoot) + " " +
                                                          std::to_string(d.median_overshoot));
  RecordProperty("rmse_blurred_deblurred",
                 std::to_string(rmse_blurred) + " " + std::to_string(rmse_deblurred));
  EXPECT_TRUE(r.report.along_columns);
  EXPECT_LT(r.report.off_axis_deg, 1.0);
  EXPECT_GT(r.report.min_length_px, 4.0);  // f ≈ 440 px, 1.6 mm of travel at 110–150 mm
  EXPECT_LT(r.report.max_length_px, 8.0);
  ASSERT_GT(d.edges, 100);
  EXPECT_GT(b.median_width_px, s.median_width_px + 3.0);
  EXPECT_LT(d.median_width_px, 0.75 * b.median_width_px);  // measured 0.69
  EXPECT_LT(d.median_overshoot, 0.2);  // the window maximum of noise x ~3 (measured 0.13)
  EXPECT_LT(rmse_deblurred, 0.9 * rmse_blurred);  // measured 0.83
  // Still: nothing to restore, the output is the input.
  const DeblurResult same =
      Deblur(sharp, still.truth_depth, camera, Eigen::Vector3d::Zero(), kExposureMs);
  EXPECT_EQ(cv::norm(same.image, sharp, cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace sewer3d
