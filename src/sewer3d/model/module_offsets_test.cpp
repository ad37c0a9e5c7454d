#include "sewer3d/model/module_offsets.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace sewer3d {
namespace {

constexpr double kRadius = 150.0;
constexpr double kDeg = std::numbers::pi / 180.0;

// Six modules 60° apart around a DN300 wall, each seeing ±38° of it (overlaps of 16°) over
// 300 mm of pipe; the wall is oval by 1 mm and has a 3 mm step at station 150 over the upper
// half. Module m reads every range `offset[m]` too long (radially, times the cosine of the
// ray's incidence, which falls from 1 at the module's centre to 0.8 at its edges), with
// 0.03 mm of noise per sample.
std::vector<ModuleWallSample> Samples(const std::vector<double>& offset, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, 0.03);
  std::vector<ModuleWallSample> out;
  for (int m = 0; m < 6; ++m) {
    for (double station = 0.0; station < 300.0; station += 1.5) {
      for (double deg = -38.0; deg <= 38.0; deg += 0.5) {
        const double clock = (60.0 * m + deg) * kDeg;
        const double cosine = 1.0 - 0.2 * (deg / 38.0) * (deg / 38.0);
        double wall = kRadius + std::cos(2.0 * clock);
        if (station > 150.0 && std::cos(clock) > 0.0) wall += 3.0;
        out.push_back({m, station, clock, wall + cosine * offset[m] + noise(rng), cosine});
      }
    }
  }
  return out;
}

TEST(ModuleOffsets, RecoverEachModulesRangeOffsetFromTheSeams) {
  const std::vector<double> truth = {0.10, -0.05, 0.02, -0.12, 0.08, -0.03};  // zero sum
  std::mt19937 rng(7);
  const ModuleOffsets got = EstimateModuleOffsets(Samples(truth, rng), 6, kRadius, {});
  ASSERT_TRUE(got.estimated) << got.why;
  // Per cell pair ~20 samples a side (0.01 mm a difference), ~100 cells a seam: ~1 µm.
  for (int m = 0; m < 6; ++m) EXPECT_NEAR(got.range_mm[m], truth[m], 0.005) << "module " << m;
  for (int m = 0; m < 6; ++m) EXPECT_GT(got.pair_cells[m], 50) << "seam " << m;
  // The seams differed by the offsets (~0.1 mm) and agree to the noise of a cell's means after.
  EXPECT_GT(got.rms_before_mm, 0.05);
  EXPECT_LT(got.rms_after_mm, 0.02);
}

TEST(ModuleOffsets, OnlyTheDifferencesAreSeenNotTheirCommonPart) {
  // The same offsets plus 0.2 mm for every module: a diameter error, which no seam shows.
  const std::vector<double> truth = {0.30, 0.15, 0.22, 0.08, 0.28, 0.17};
  std::mt19937 rng(8);
  const ModuleOffsets got = EstimateModuleOffsets(Samples(truth, rng), 6, kRadius, {});
  ASSERT_TRUE(got.estimated) << got.why;
  double sum = 0.0;
  for (const double x : got.range_mm) sum += x;
  EXPECT_NEAR(sum, 0.0, 1e-6);
  for (int m = 0; m < 6; ++m) EXPECT_NEAR(got.range_mm[m], truth[m] - 0.2, 0.01) << m;
}

TEST(ModuleOffsets, ModulesThatDoNotOverlapGetNone) {
  std::mt19937 rng(9);
  std::vector<ModuleWallSample> samples = Samples({0.1, 0, 0, 0, 0, -0.1}, rng);
  // Module 3 saw nothing: modules 0–2 and 4–5 are two chains with nothing between them.
  std::erase_if(samples, [](const ModuleWallSample& s) { return s.module == 3; });
  const ModuleOffsets got = EstimateModuleOffsets(samples, 6, kRadius, {});
  EXPECT_FALSE(got.estimated);
  EXPECT_NE(got.why.find("do not join"), std::string::npos) << got.why;
  for (const double x : got.range_mm) EXPECT_EQ(x, 0.0);
}

TEST(ModuleOffsets, AnOffsetNoCalibrationLeavesIsNotApplied) {
  std::mt19937 rng(10);
  const ModuleOffsets got =
      EstimateModuleOffsets(Samples({0.9, -0.9, 0.9, -0.9, 0.9, -0.9}, rng), 6, kRadius,
                            {.max_difference_mm = 5.0, .max_offset_mm = 0.5});
  EXPECT_FALSE(got.estimated);
  EXPECT_NE(got.why.find("no calibration error"), std::string::npos) << got.why;
}

}  // namespace
}  // namespace sewer3d
