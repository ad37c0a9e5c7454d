// Texture → pattern instant on rendered triplets (648 x 486): a DN300 wall 110 mm from the
// camera, the camera moving along the pipe (camera y). The speed is 400 mm/s so that at the
// reduced size the images move as far in pixels as at full size at 100 mm/s (~16 px between
// texture_before and texture_after, ±8 px from the pattern instant). Truth: a render at the pattern
// instant with the same options (same motion blur), so only the registration differs.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/material.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/testing/small_module.hpp"
#include "sewer3d/texture/triplet_mapping.hpp"

namespace sewer3d {
namespace {

constexpr double kSpeedMmS = 400.0, kExposureMs = 4.0, kGapS = 0.005;

// A scene seen from a camera displaced by `shift_mm` along camera y (no rotation).
class ShiftedScene final : public Surface {
 public:
  ShiftedScene(const Scene& scene, double shift_mm) : scene_(scene), shift_(0, shift_mm, 0) {}
  std::optional<SurfaceHit> Intersect(const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction) const override {
    auto hit = sewer3d::Intersect(scene_, origin + shift_, direction);
    if (hit) hit->point -= shift_;
    return hit;
  }
  std::uint64_t MaterialSeed() const override { return scene_.material_seed; }

 private:
  const Scene& scene_;
  Eigen::Vector3d shift_;
};

Scene Wall(Material material) {
  Scene s;
  s.type = Scene::Type::kCylinder;
  s.diameter_mm = 300.0;
  s.axis_point_mm = {0.0, 0.0, -40.0};  // camera 40 mm off the axis: the wall 110 mm away
  s.material = material;
  return s;
}

struct Rendered {
  cv::Mat3f texture;
  cv::Mat1f depth;
};

Rendered Render(const ModuleDescription& module, const Scene& scene, double time_s,
                std::uint64_t seed) {
  RenderOptions o;
  o.images = RenderImages::kTexture;
  o.speed_mm_s = kSpeedMmS;
  o.exposure_ms = kExposureMs;
  o.seed = seed;
  const RenderedFrame f =
      RenderFrame(module, BinaryArray(1, 1), ShiftedScene(scene, kSpeedMmS * time_s), o);
  Rendered r;
  f.texture.convertTo(r.texture, CV_32F);
  r.depth = f.truth_depth;
  return r;
}

// Median |shift| (px) of 64 x 64 tiles with depth between `image` and `truth`, by phase
// correlation of their grey levels, high-passed: the texture light moves with the camera, so
// the illumination's falloff stays put in the image and would pull the peak to zero.
cv::Mat1f HighPassGrey(const cv::Mat3f& image) {
  cv::Mat1f grey, low;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  cv::GaussianBlur(grey, low, cv::Size(), 4.0);
  return grey - low;
}

double MedianMisregistrationPx(const cv::Mat3f& image, const cv::Mat3f& truth,
                               const cv::Mat1f& depth) {
  const cv::Mat1f a = HighPassGrey(image), b = HighPassGrey(truth);
  cv::Mat1f window;
  constexpr int kTile = 64;
  cv::createHanningWindow(window, cv::Size(kTile, kTile), CV_32F);
  std::vector<double> shifts;
  for (int v = 16; v + kTile <= image.rows - 16; v += kTile / 2) {
    for (int u = 16; u + kTile <= image.cols - 16; u += kTile / 2) {
      const cv::Rect tile(u, v, kTile, kTile);
      if (cv::countNonZero(depth(tile) > 0.0F) < kTile * kTile) continue;
      const cv::Point2d d = cv::phaseCorrelate(a(tile), b(tile), window);
      shifts.push_back(std::hypot(d.x, d.y));
    }
  }
  if (shifts.empty()) return NAN;
  std::nth_element(shifts.begin(), shifts.begin() + shifts.size() / 2, shifts.end());
  return shifts[shifts.size() / 2];
}

class TripletMapping : public ::testing::Test {
 protected:
  void RenderTriplet(Material material) {
    module_ = testing::SmallDefaultModule(648);
    scene_ = Wall(material);
    before_ = Render(module_, scene_, -kGapS, 11);
    truth_ = Render(module_, scene_, 0.0, 12);
    after_ = Render(module_, scene_, kGapS, 13);
  }
  ModuleDescription module_;
  Scene scene_;
  Rendered before_, truth_, after_;
  const TripletTimes times_{0.0, kGapS, 2 * kGapS};
  const Eigen::Vector3d velocity_{0.0, kSpeedMmS, 0.0};
};

TEST_F(TripletMapping, AkazeMotionRegistersTheTextureToThePatternInstant) {
  RenderTriplet(Material::kConcrete);
  const CameraModel camera(module_.camera);
  const TripletMappingResult r =
      MapTripletToPattern(before_.texture, after_.texture, truth_.depth, camera, times_);
  const double mapped = MedianMisregistrationPx(r.color, truth_.texture, truth_.depth);
  const double naive = MedianMisregistrationPx(before_.texture, truth_.texture, truth_.depth);
  RecordProperty("features", std::to_string(r.report.features_before));
  RecordProperty("matches_inliers",
                 std::to_string(r.report.matches) + " " + std::to_string(r.report.inliers));
  RecordProperty("rms_px", std::to_string(r.report.reprojection_rms_px));
  RecordProperty("time_ms", std::to_string(r.report.time_ms));
  RecordProperty("motion_mm_deg",
                 std::to_string(r.report.motion_mm) + " " + std::to_string(r.report.rotation_deg));
  RecordProperty("misregistration_px", std::to_string(mapped) + " naive " + std::to_string(naive));
  ASSERT_EQ(r.report.method, "akaze");
  EXPECT_GE(r.report.inliers, 30);
  EXPECT_LT(r.report.reprojection_rms_px, 0.5);
  // True motion: 4 mm along camera y (10 ms at 400 mm/s), no rotation.
  EXPECT_NEAR(r.after_from_before.translation.y(), -2 * kGapS * kSpeedMmS, 0.15);
  EXPECT_LT(r.report.rotation_deg, 0.1);
  EXPECT_GT(naive, 3.0);
  EXPECT_LT(mapped, 0.5);
}

TEST_F(TripletMapping, OdometryMotionAlsoRegisters) {
  RenderTriplet(Material::kConcrete);
  TripletMappingOptions no_features;
  no_features.min_inliers = 1000000;
  const TripletMappingResult r =
      MapTripletToPattern(before_.texture, after_.texture, truth_.depth,
                          CameraModel(module_.camera), times_, velocity_, no_features);
  EXPECT_EQ(r.report.method, "odometry");
  EXPECT_NEAR(r.report.motion_mm, 2 * kGapS * kSpeedMmS, 1e-9);
  EXPECT_LT(MedianMisregistrationPx(r.color, truth_.texture, truth_.depth), 0.5);
}

TEST_F(TripletMapping, FeaturelessWallFallsBackAndSaysSo) {
  RenderTriplet(Material::kPlastic);
  const CameraModel camera(module_.camera);
  const TripletMappingResult odo =
      MapTripletToPattern(before_.texture, after_.texture, truth_.depth, camera, times_, velocity_);
  RecordProperty("plastic_matches_inliers",
                 std::to_string(odo.report.matches) + " " + std::to_string(odo.report.inliers));
  EXPECT_EQ(odo.report.method, "odometry");
  EXPECT_GT(odo.report.mapped_pixels, 0);
  const TripletMappingResult none =
      MapTripletToPattern(before_.texture, after_.texture, truth_.depth, camera, times_);
  EXPECT_EQ(none.report.method, "none");
  EXPECT_EQ(none.report.mapped_pixels, 0);
  EXPECT_EQ(cv::norm(none.color, before_.texture, cv::NORM_INF), 0.0);
}

TEST(InterpolatePose, EndsAndMidpoint) {
  const Rigid3d a(Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX())),
                  Eigen::Vector3d(1, 2, 3));
  const Rigid3d b(Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitX())),
                  Eigen::Vector3d(3, 2, 1));
  EXPECT_LT(InterpolatePose(a, b, 0.0).rotation.angularDistance(a.rotation), 1e-12);
  EXPECT_LT(InterpolatePose(a, b, 1.0).rotation.angularDistance(b.rotation), 1e-12);
  const Rigid3d mid = InterpolatePose(a, b, 0.5);
  EXPECT_NEAR(Eigen::AngleAxisd(mid.rotation).angle(), 0.4, 1e-12);
  EXPECT_LT((mid.translation - Eigen::Vector3d(2, 2, 2)).norm(), 1e-12);
}

TEST(TripletTimes, MustBeOrdered) {
  EXPECT_THROW((TripletTimes{0.0, 0.02, 0.01}.Check()), std::invalid_argument);
  EXPECT_THROW((TripletTimes{0.01, 0.01, 0.01}.Check()), std::invalid_argument);
  EXPECT_NO_THROW((TripletTimes{0.0, 0.005, 0.01}.Check()));
}

}  // namespace
}  // namespace sewer3d
