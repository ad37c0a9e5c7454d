#include "sewer3d/inspect/texture_cracks.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"

namespace sewer3d {
namespace {

constexpr double kRadius = 150.0;
constexpr double kCell = 0.4;  // fine map cell: the grey map is the fine map

// A wall like the simulator's concrete at 0.4 mm: mid-grey cement, angular grains 2–6 mm
// across from dark to light, some of them outlined by a thin dark line (the material's own
// hairlines, a few mm long), dark pores, and pixel noise. Drawn three times a turn apart so the
// texture runs on across 12 o'clock.
cv::Mat3b ConcreteTexture(const MapGrid& grid, unsigned seed) {
  cv::RNG rng(seed);
  cv::Mat1b grey(grid.rows, grid.cols, static_cast<unsigned char>(128));
  const double area = grid.rows * grid.cols * kCell * kCell;
  const int grains = static_cast<int>(area / 30.0), pores = static_cast<int>(area / 20.0);
  const auto draw = [&](auto&& shape) {
    for (int shift = -1; shift <= 1; ++shift) shape(shift * grid.cols);
  };
  for (int i = 0; i < grains; ++i) {
    const cv::Point2d centre(rng.uniform(0.0, static_cast<double>(grid.cols)),
                             rng.uniform(0.0, static_cast<double>(grid.rows)));
    const double radius = rng.uniform(1.0, 3.0) / kCell;
    const int sides = rng.uniform(5, 8);
    std::vector<cv::Point> corners;
    for (int k = 0; k < sides; ++k) {
      const double a = 2.0 * std::numbers::pi * (k + rng.uniform(-0.3, 0.3)) / sides;
      corners.emplace_back(static_cast<int>(centre.x + radius * std::cos(a)),
                           static_cast<int>(centre.y + radius * std::sin(a)));
    }
    const int level = rng.uniform(70, 200);
    const bool outlined = rng.uniform(0.0, 1.0) < 0.3;
    draw([&](int dx) {
      std::vector<cv::Point> moved = corners;
      for (cv::Point& p : moved) p.x += dx;
      cv::fillConvexPoly(grey, moved, cv::Scalar(level));
      if (outlined) cv::polylines(grey, moved, true, cv::Scalar(60), 1);
    });
  }
  for (int i = 0; i < pores; ++i) {
    const cv::Point centre(rng.uniform(0, grid.cols), rng.uniform(0, grid.rows));
    const int radius = rng.uniform(1, 3);
    draw([&](int dx) { cv::circle(grey, centre + cv::Point(dx, 0), radius, cv::Scalar(50), -1); });
  }
  cv::Mat1f noise(grey.size());
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 4.0);
  cv::Mat1f level;
  grey.convertTo(level, CV_32F);
  cv::GaussianBlur(level + noise, level, cv::Size(0, 0), 0.7);  // the texture's own blur
  cv::Mat1b out;
  level.convertTo(out, CV_8U);
  cv::Mat3b bgr;
  cv::cvtColor(out, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

struct Line {
  double station_mm, clock_h, length_mm, angle_deg, width_mm;
};

// A dark crack drawn into the texture: `width_mm` open (cells covered in part darkened in
// part), its middle at (station, clock), running on across 12 o'clock.
void DrawCrack(cv::Mat3b& texture, const MapGrid& grid, const Line& k) {
  const double a = DegToRad(k.angle_deg);
  const double s0 = k.station_mm, c0 = ClockHoursToRad(k.clock_h) * kRadius;  // mm
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      const double ds = (r + 0.5) * kCell + grid.station0_mm - s0;
      const double dc = std::remainder((c + 0.5) * kCell - c0, grid.cols * kCell);
      const double along = ds * std::cos(a) + dc * std::sin(a);
      const double across = std::abs(-ds * std::sin(a) + dc * std::cos(a));
      if (std::abs(along) > 0.5 * k.length_mm) continue;
      const double cover = std::clamp((0.5 * k.width_mm - across) / kCell + 0.5, 0.0, 1.0);
      texture(r, c) = texture(r, c) * (1.0 - cover) + cv::Vec3b(35, 35, 35) * cover;
    }
  }
}

PipeMaps Maps(const MapGrid& grid, const cv::Mat3b& texture) {
  PipeMaps maps;
  maps.grid = grid;
  maps.texture = texture;
  maps.displacement_mm = cv::Mat1f::zeros(grid.rows, grid.cols);
  maps.samples = cv::Mat1w::ones(grid.rows, grid.cols);
  maps.coverage = cv::Mat1b(grid.rows, grid.cols, static_cast<unsigned char>(Coverage::kMeasured));
  return maps;
}

CoarseMap Coarse(const PipeMaps& maps) {
  CoarseMapBuilder builder(maps.grid, 1.0, kCell);
  builder.Add(maps);
  return builder.Finish();
}

const MapGrid kGrid = MakeMapGrid(0.0, 240.0, kRadius, kCell);

TEST(TextureCracks, FindsACrackTheTextureShows) {
  cv::Mat3b texture = ConcreteTexture(kGrid, 3);
  DrawCrack(texture, kGrid, {120.0, 4.5, 100.0, 20.0, 1.6});
  const std::vector<Observation> found =
      FindTextureCracks(Coarse(Maps(kGrid, texture)), kRadius, {}, {});
  ASSERT_EQ(found.size(), 1U);
  const Observation& o = found[0];
  EXPECT_EQ(o.code, "BAB");
  EXPECT_NEAR(o.station_mm, 120.0, 2.0);
  EXPECT_NEAR(o.clock_h, 4.5, 0.05);
  // The ends fade into the response's averaging (± half_length_mm) and the grow threshold.
  ASSERT_NE(o.Find("length_mm"), nullptr);
  EXPECT_NEAR(o.Find("length_mm")->value, 100.0, 8.0);
  EXPECT_NEAR(o.Find("angle_deg")->value, 20.0, 1.5);
  ASSERT_NE(o.Find("width_mm"), nullptr);
  EXPECT_NEAR(o.Find("width_mm")->value, 1.6, 0.4);
  EXPECT_GT(o.confidence, 0.5);
}

TEST(TextureCracks, FindsNoneInTheMaterialsOwnMarksSeamsAndHoles) {
  for (const unsigned seed : {3U, 5U}) {
    cv::Mat3b texture = ConcreteTexture(kGrid, seed);
    // A seam between two modules' textures (a brightness step along the pipe), a hole too
    // wide for a crack (a lost patch), and a row of lost spots (3 mm holes 6 mm apart).
    texture.colRange(0, kGrid.cols / 3) *= 0.8;
    PipeMaps maps = Maps(kGrid, texture);
    cv::rectangle(maps.coverage, cv::Rect(1500, 200, 60, 50), cv::Scalar(0), -1);
    for (int i = 0; i < 20; ++i)
      cv::circle(maps.coverage, cv::Point(800 + 15 * i, 400), 4, cv::Scalar(0), -1);
    const std::vector<Observation> found = FindTextureCracks(Coarse(maps), kRadius, {}, {});
    for (const Observation& o : found) ADD_FAILURE() << "seed " << seed << ": " << o.remark;
  }
}

TEST(TextureCracks, FollowsACrackAcrossTheCrownAndThroughLostSpots) {
  cv::Mat3b texture = ConcreteTexture(kGrid, 7);
  DrawCrack(texture, kGrid, {100.0, 12.0, 120.0, 60.0, 1.2});
  PipeMaps maps = Maps(kGrid, texture);
  // The depth maps lost the spots in the crack every 15 mm: narrow holes along it.
  const double a = DegToRad(60.0);
  for (int i = -3; i <= 3; ++i) {
    const double t = 15.0 * i;
    const cv::Point2d p(std::fmod(t * std::sin(a) / kCell + kGrid.cols, kGrid.cols),
                        (100.0 + t * std::cos(a)) / kCell);
    cv::circle(maps.coverage, p, 3, cv::Scalar(0), -1);
  }
  const std::vector<Observation> found = FindTextureCracks(Coarse(maps), kRadius, {}, {});
  ASSERT_EQ(found.size(), 1U);
  EXPECT_NEAR(found[0].station_mm, 100.0, 2.0);
  EXPECT_NEAR(std::remainder(found[0].clock_h - 12.0, 12.0), 0.0, 0.05);
  EXPECT_NEAR(found[0].Find("length_mm")->value, 120.0, 10.0);
  EXPECT_NEAR(found[0].Find("angle_deg")->value, 60.0, 1.5);
}

TEST(TextureCracks, LeavesExcludedRegionsAndDisabledSearchAlone) {
  cv::Mat3b texture = ConcreteTexture(kGrid, 3);
  DrawCrack(texture, kGrid, {120.0, 4.5, 100.0, 20.0, 1.6});
  const CoarseMap map = Coarse(Maps(kGrid, texture));
  const int col = static_cast<int>(4.5 / 12.0 * kGrid.cols);
  const MapCrop around{static_cast<int>(60.0 / kCell), static_cast<int>(120.0 / kCell), col - 150,
                       300};
  EXPECT_TRUE(FindTextureCracks(map, kRadius, {around}, {}).empty());
  TextureCrackOptions off;
  off.enabled = false;
  EXPECT_TRUE(FindTextureCracks(map, kRadius, {}, off).empty());
  TextureCrackOptions bad;
  bad.seed_sigmas = 2.0;  // below grow_sigmas
  EXPECT_THROW(FindTextureCracks(map, kRadius, {}, bad), InvalidValue);
}

}  // namespace
}  // namespace sewer3d
