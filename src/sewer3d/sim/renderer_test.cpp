#include "sewer3d/sim/renderer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <vector>

#include "sewer3d/core/units.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/material.hpp"
#include "sewer3d/sim/scene_presets.hpp"
#include "sewer3d/sim/spot_truth.hpp"
#include "sewer3d/sim/surface.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

ModuleDescription SmallModule() { return testing::SmallDefaultModule(648); }

// Intensity centroid of `image` in a (2r+1)² window around `centre`.
std::optional<Eigen::Vector2d> Centroid(const cv::Mat1f& image, const Eigen::Vector2d& centre,
                                        int r) {
  const int cu = static_cast<int>(std::round(centre.x())),
            cv_ = static_cast<int>(std::round(centre.y()));
  if (cu - r < 0 || cv_ - r < 0 || cu + r >= image.cols || cv_ + r >= image.rows)
    return std::nullopt;
  double sum = 0, su = 0, sv = 0;
  for (int v = cv_ - r; v <= cv_ + r; ++v) {
    for (int u = cu - r; u <= cu + r; ++u) {
      sum += image(v, u);
      su += image(v, u) * u;
      sv += image(v, u) * v;
    }
  }
  if (sum <= 0) return std::nullopt;
  return Eigen::Vector2d(su / sum, sv / sum);
}

TEST(Renderer, IdealSpotsLieOnTheProjectedElementCentres) {
  const ModuleDescription module = SmallModule();
  const BinaryArray pattern = DefaultPatternArray();
  Scene plane;
  plane.distance_mm = 140.0;
  plane.tilt_deg = 10.0;
  plane.material = Material::kPlastic;
  RenderOptions options = RenderOptions::Ideal();
  options.supersampling = 8;
  const RenderedFrame frame = RenderFrame(module, pattern, plane, options);

  // Independent geometry: projector ray through each spot's element centre, meet the plane,
  // project into the camera.
  double worst = 0.0;
  int checked = 0;
  for (const Eigen::Vector2d& expected : ProjectedSpotCentres(module, pattern, plane)) {
    const auto centroid = Centroid(frame.pattern_signal, expected, 5);
    if (!centroid) continue;
    worst = std::max(worst, (*centroid - expected).norm());
    ++checked;
  }
  RecordProperty("worst_centroid_error_px", std::to_string(worst));
  RecordProperty("spots_checked", checked);
  EXPECT_GT(checked, 500);
  EXPECT_LT(worst, 0.05);
}

TEST(Renderer, TruthDepthMatchesAnalyticSurfaces) {
  const ModuleDescription module = SmallModule();
  const CameraModel camera(module.camera);
  RenderOptions options = RenderOptions::Ideal();
  options.supersampling = 1;
  Scene plane;
  plane.distance_mm = 90.0;
  plane.tilt_deg = -15.0;
  const cv::Mat1f plane_depth =
      RenderFrame(module, DefaultPatternArray(), plane, options).truth_depth;
  Scene cylinder;
  cylinder.type = Scene::Type::kCylinder;
  cylinder.diameter_mm = 200.0;
  cylinder.axis_point_mm = {5.0, 0.0, 15.0};
  const cv::Mat1f cylinder_depth =
      RenderFrame(module, DefaultPatternArray(), cylinder, options).truth_depth;
  double worst_plane = 0.0, worst_cylinder = 0.0;
  for (int v = 0; v < module.camera.height; v += 7) {
    for (int u = 0; u < module.camera.width; u += 7) {
      const Eigen::Vector2d xy = *camera.Unproject({double(u), double(v)});
      const double tan_tilt = std::tan(DegToRad(-15.0));
      worst_plane =
          std::max(worst_plane, std::abs(plane_depth(v, u) - 90.0 / (1.0 - xy.y() * tan_tilt)));
      // (z x − 5)² + (z − 15)² = 100², far root.
      const double a = xy.x() * xy.x() + 1, b = -2 * (5 * xy.x() + 15), c = 25 + 225 - 10000.0;
      const double z = (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
      worst_cylinder = std::max(worst_cylinder, std::abs(cylinder_depth(v, u) - z));
    }
  }
  // float32 storage: 1e-4 mm is ~1.5 ulp at 225 mm.
  RecordProperty("worst_plane_depth_error_mm", std::to_string(worst_plane));
  RecordProperty("worst_cylinder_depth_error_mm", std::to_string(worst_cylinder));
  EXPECT_LT(worst_plane, 1e-4);
  EXPECT_LT(worst_cylinder, 1e-4);
}

// Projector and camera look from 78 mm apart, so at a depth step the camera sees wall that
// the projector cannot reach (a joint's gap behind its edge, the wall beside an intrusion). No
// pattern light may land there. The renderer once lit it: ghost spots in the shadow band,
// which a real module never shows, claimed the elements of the true spots beside the step.
TEST(Renderer, NoPatternLightWhereTheProjectorCannotSee) {
  const ModuleDescription module = SmallModule();
  const CameraModel camera(module.camera);
  Scene wall;
  wall.type = Scene::Type::kPipeWall;
  wall.features = PipeWallPresetFeatures();
  RenderOptions options = RenderOptions::Ideal();  // no ambient light
  options.supersampling = 1;
  const RenderedFrame frame = RenderFrame(module, DefaultPatternArray(), wall, options);
  // Pixel centres hidden from the projector by 2 mm or more, tested independently of the
  // renderer: the first wall the projector's ray meets lies that far before the point.
  const Eigen::Vector3d projector = module.projector_from_camera.Inverse().translation;
  cv::Mat1b hidden(frame.truth_depth.size(), 0);
  for (int v = 0; v < hidden.rows; ++v) {
    for (int u = 0; u < hidden.cols; ++u) {
      const float z = frame.truth_depth(v, u);
      if (!std::isfinite(z)) continue;
      const Eigen::Vector2d xy = *camera.Unproject({double(u), double(v)});
      const Eigen::Vector3d ray = double(z) * Eigen::Vector3d(xy.x(), xy.y(), 1.0) - projector;
      const auto first = Intersect(wall, projector, ray);
      hidden(v, u) = first && first->t < 1.0 - 2.0 / ray.norm() ? 255 : 0;
    }
  }
  // A pixel's one sample lies anywhere in it: judge the pixels whose neighbours are hidden too.
  cv::erode(hidden, hidden, cv::Mat1b(3, 3, 255));
  int hidden_pixels = 0;
  float hidden_light = 0.0F;
  for (int v = 0; v < hidden.rows; ++v) {
    for (int u = 0; u < hidden.cols; ++u) {
      if (!hidden(v, u)) continue;
      ++hidden_pixels;
      hidden_light = std::max(hidden_light, frame.pattern_signal(v, u));
    }
  }
  RecordProperty("hidden_pixels", hidden_pixels);
  EXPECT_GT(hidden_pixels, 500);  // the joint's and the intrusion's shadow bands
  EXPECT_EQ(hidden_light, 0.0F);
  EXPECT_GT(cv::sum(frame.pattern_signal)[0], 0.0);
}

TEST(Renderer, ProjectorDefocusGrowsAwayFromFocus) {
  const ModuleDescription module = SmallModule();
  RenderOptions options = RenderOptions::Ideal();
  options.projector_focus_mm = 112.5;
  // Spot size: pixels above half of the local maximum, per 16 x 16 tile holding light.
  auto spread = [&](double distance) {
    Scene plane;
    plane.distance_mm = distance;
    plane.material = Material::kPlastic;
    const cv::Mat1f image =
        RenderFrame(module, DefaultPatternArray(), plane, options).pattern_signal;
    double area = 0.0, image_max = 0.0;
    int tiles = 0;
    cv::minMaxLoc(image, nullptr, &image_max);
    for (int v = 0; v + 16 <= image.rows; v += 16) {
      for (int u = 0; u + 16 <= image.cols; u += 16) {
        const cv::Mat1f tile = image(cv::Rect(u, v, 16, 16));
        double max_value;
        cv::minMaxLoc(tile, nullptr, &max_value);
        if (max_value <= 0.2 * image_max) continue;  // tiles holding a spot, not only tails
        area += cv::countNonZero(tile > 0.5 * max_value);
        ++tiles;
      }
    }
    return area / tiles;
  };
  // Thin lens, f/2: circle of confusion f·D·|1/75 − 1/112.5| ≈ 3.7 projector px at 75 mm.
  options.projector_f_number = 2.0;
  // A 4 px disk blurred by sigma 1.46 px: its half-maximum area grows by about half.
  EXPECT_GT(spread(75.0), 1.3 * spread(112.5));
}

TEST(Renderer, SubsurfaceScatteringSpreadsSpotsWithoutMovingThem) {
  const ModuleDescription module = SmallModule();
  const BinaryArray pattern = DefaultPatternArray();
  Scene plane;
  plane.distance_mm = 140.0;
  plane.material = Material::kPlastic;
  RenderOptions options = RenderOptions::Ideal();
  const cv::Mat1f sharp = RenderFrame(module, pattern, plane, options).pattern_signal;
  // 0.5 mm at 140 mm: a Gaussian of 1.55 projector px for the 648 px module (f 434 px)
  // beside the 0.3 px of the optics, on a disk of radius 2 px.
  options.spot_errors.subsurface_plastic_mm = 0.5;
  const cv::Mat1f spread = RenderFrame(module, pattern, plane, options).pattern_signal;
  options.spot_errors.subsurface_plastic_mm = 0.0;
  options.spot_errors.subsurface_mm = 0.5;  // concrete's, not plastic's: no change here
  const cv::Mat1f mineral = RenderFrame(module, pattern, plane, options).pattern_signal;
  EXPECT_EQ(cv::norm(mineral, sharp, cv::NORM_INF), 0.0);
  double sharp_max, spread_max;
  cv::minMaxLoc(sharp, nullptr, &sharp_max);
  cv::minMaxLoc(spread, nullptr, &spread_max);
  // The light is kept (the blur is normalised), the peaks fall, the centres stay.
  // (The spots at the image's edge lose their wider tails: 2 % measured.)
  EXPECT_NEAR(cv::sum(spread)[0], cv::sum(sharp)[0], 0.03 * cv::sum(sharp)[0]);
  EXPECT_LT(spread_max, 0.8 * sharp_max);
  Eigen::Vector2d mean_error = Eigen::Vector2d::Zero();
  double worst = 0.0;
  int checked = 0;
  for (const Eigen::Vector2d& expected : ProjectedSpotCentres(module, pattern, plane)) {
    const auto centroid = Centroid(spread, expected, 5);
    if (!centroid) continue;
    mean_error += *centroid - expected;
    worst = std::max(worst, (*centroid - expected).norm());
    ++checked;
  }
  ASSERT_GT(checked, 500);
  // No bias; single centroids move by the wider tails the 11 px window cuts (0.09 px).
  RecordProperty("worst_centroid_error_px", std::to_string(worst));
  EXPECT_LT((mean_error / checked).norm(), 0.01);
  EXPECT_LT(worst, 0.15);
}

TEST(Renderer, DeterministicForASeedAndNoiseMatchesTheSensorModel) {
  const ModuleDescription module = SmallModule();
  Scene plane;
  plane.distance_mm = 150.0;
  plane.material = Material::kPlastic;
  RenderOptions options;
  options.supersampling = 1;
  const RenderedFrame a = RenderFrame(module, DefaultPatternArray(), plane, options);
  const RenderedFrame b = RenderFrame(module, DefaultPatternArray(), plane, options);
  EXPECT_EQ(cv::norm(a.texture, b.texture, cv::NORM_INF), 0.0);
  options.seed = 2;
  const RenderedFrame c = RenderFrame(module, DefaultPatternArray(), plane, options);
  EXPECT_GT(cv::norm(a.texture, c.texture, cv::NORM_INF), 0.0);
  // Noise in a flat region: residual of DN against the expected signal, green channel.
  double sum = 0, sum2 = 0, expected_var = 0;
  int count = 0;
  for (int v = 200; v < 280; ++v) {
    for (int u = 280; u < 360; ++u) {
      const double signal = a.texture_signal(v, u)[1];
      const double dn = a.texture(v, u)[1];
      const double r = dn - signal * 255.0;
      sum += r;
      sum2 += r * r;
      const double e = signal * options.sensor.full_well_e;
      expected_var += (e + 9.0) / std::pow(options.sensor.full_well_e / 255.0, 2) + 1.0 / 12.0;
      ++count;
    }
  }
  const double measured = std::sqrt(sum2 / count), expected = std::sqrt(expected_var / count);
  EXPECT_NEAR(measured, expected, 0.1 * expected);  // 6400 samples: ~1 % statistical error
  EXPECT_NEAR(sum / count, 0.0, 0.1);
}

TEST(Renderer, MotionBlurSmearsTheTextureAlongTheMotion) {
  // Camera, projector and light move together: on a wall parallel to the motion the spots stay
  // put in the image, while the wall's texture slides by speed x exposure.
  const ModuleDescription module = SmallModule();
  Scene plane;
  plane.distance_mm = 150.0;
  plane.material = Material::kConcrete;
  RenderOptions options = RenderOptions::Ideal();
  // Gradient energy across u over along v: blur along v smooths the image along v.
  auto anisotropy = [&](double speed_mm_s) {
    options.speed_mm_s = speed_mm_s;
    options.exposure_ms = 10.0;  // 1 mm of travel along camera y: ~2.9 px at 150 mm
    cv::Mat1f image;
    cv::extractChannel(RenderFrame(module, DefaultPatternArray(), plane, options).texture_signal,
                       image, 1);
    double across = 0.0, along = 0.0;
    for (int v = 0; v + 1 < image.rows; ++v) {
      for (int u = 0; u + 1 < image.cols; ++u) {
        across += std::pow(image(v, u + 1) - image(v, u), 2);
        along += std::pow(image(v + 1, u) - image(v, u), 2);
      }
    }
    return across / along;
  };
  const double still = anisotropy(0.0), moving = anisotropy(100.0);
  EXPECT_NEAR(still, 1.0, 0.15);
  EXPECT_GT(moving, 1.3 * still);
}

// A plane at z = 150 mm printed dark above y = 0 and light below: an edge across the image.
class EdgePlane final : public Surface {
 public:
  std::optional<SurfaceHit> Intersect(const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction) const override {
    if (direction.z() <= 0) return std::nullopt;
    SurfaceHit hit;
    hit.t = (150.0 - origin.z()) / direction.z();
    hit.point = origin + hit.t * direction;
    hit.normal = -Eigen::Vector3d::UnitZ();
    hit.surface_mm = hit.point.head<2>();
    hit.albedo = Eigen::Vector3d::Constant(hit.point.y() < 0.0 ? 0.2 : 0.8);
    return hit;
  }
  std::uint64_t MaterialSeed() const override { return 1; }
};

// 10–90 % rise (px) of the edge along v in the green channel, column `u` (the lens bends the
// edge elsewhere).
double EdgeWidthPx(const cv::Mat3f& texture, int u) {
  std::vector<double> profile;
  for (int v = 0; v < texture.rows; ++v) profile.push_back(texture(v, u)[1]);
  // The edge is the largest rise; its levels are read 10 px to either side (the light's falloff
  // changes them by under 1 % there).
  int edge = 1;
  for (int v = 1; v < texture.rows; ++v) {
    if (profile[v] - profile[v - 1] > profile[edge] - profile[edge - 1]) edge = v;
  }
  const double lo = profile[std::max(0, edge - 10)];
  const double hi = profile[std::min(texture.rows - 1, edge + 10)];
  auto crossing = [&](double level) -> double {
    for (int v = std::max(1, edge - 10); v <= std::min(texture.rows - 1, edge + 10); ++v) {
      if (profile[v] >= level && profile[v - 1] < level)
        return v - 1 + (level - profile[v - 1]) / (profile[v] - profile[v - 1]);
    }
    return NAN;
  };
  return crossing(lo + 0.9 * (hi - lo)) - crossing(lo + 0.1 * (hi - lo));
}

// With one sample per pixel the exposure cannot be sampled: the blur is applied afterwards
// along each pixel's image path. A box of length L has a 10–90 % rise of 0.8 L (plus the
// pixel's own step); 1 mm of travel at 150 mm is L = f / 150 px.
TEST(Renderer, OneSampleRendersGetTheMotionBlurOfTheExposure) {
  const ModuleDescription module = SmallModule();
  RenderOptions options = RenderOptions::Ideal();
  options.images = RenderImages::kTexture;
  options.supersampling = 1;
  options.exposure_ms = 10.0;
  const EdgePlane edge;
  auto width = [&](double speed_mm_s) {
    options.speed_mm_s = speed_mm_s;
    return EdgeWidthPx(RenderFrame(module, DefaultPatternArray(), edge, options).texture_signal,
                       static_cast<int>(module.camera.cx));
  };
  const double length_px = module.camera.fy * 1.0 / 150.0;
  const double still = width(0.0), moving = width(100.0);
  RecordProperty("widths", std::to_string(still) + " " + std::to_string(moving));
  EXPECT_LT(still, 1.0);
  EXPECT_NEAR(moving, 0.8 * length_px, 0.5);
}

TEST(Materials, ConcreteVariesAndPlasticIsNearlyUniform) {
  auto spread = [](Material m) {
    double sum = 0, sum2 = 0;
    int n = 0;
    for (double x = 0; x < 200; x += 0.7) {
      for (double y = 0; y < 200; y += 0.7) {
        const double g = MaterialAlbedo(m, 3, {x, y}).mean();
        sum += g;
        sum2 += g * g;
        ++n;
      }
    }
    const double mean = sum / n;
    return std::sqrt(sum2 / n - mean * mean) / mean;
  };
  EXPECT_GT(spread(Material::kConcrete), 0.08);
  EXPECT_GT(spread(Material::kVitrifiedClay), 0.03);
  EXPECT_LT(spread(Material::kPlastic), 0.02);
}

}  // namespace
}  // namespace sewer3d
