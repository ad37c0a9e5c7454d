#include "sewer3d/report/map_downsample.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <random>

namespace sewer3d {
namespace {

PipeMaps RandomMaps(int rows, int cols, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(-5.0F, 5.0F);
  std::uniform_int_distribution<int> byte(0, 255), cover(0, 3);
  PipeMaps m;
  m.grid.rows = rows;
  m.grid.cols = cols;
  m.texture = cv::Mat3b(rows, cols);
  m.displacement_mm = cv::Mat1f(rows, cols);
  m.samples = cv::Mat1w(rows, cols, 1);
  m.coverage = cv::Mat1b(rows, cols);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const bool covered = cover(rng) != 0;
      m.coverage(r, c) = covered ? 1 : 0;
      m.texture(r, c) = covered ? cv::Vec3b(byte(rng), byte(rng), byte(rng)) : cv::Vec3b(0, 0, 0);
      m.displacement_mm(r, c) = covered ? d(rng) : std::numeric_limits<float>::quiet_NaN();
    }
  }
  return m;
}

PipeMaps Rows(const PipeMaps& m, int row0, int rows) {
  PipeMaps t;
  t.texture = m.texture.rowRange(row0, row0 + rows).clone();
  t.displacement_mm = m.displacement_mm.rowRange(row0, row0 + rows).clone();
  t.samples = m.samples.rowRange(row0, row0 + rows).clone();
  t.coverage = m.coverage.rowRange(row0, row0 + rows).clone();
  return t;
}

TEST(MapDownsample, FactorBringsSizeUnderTheLimit) {
  EXPECT_EQ(DownsampleFactor(5817, 4096), 2);
  EXPECT_EQ(DownsampleFactor(4096, 4096), 1);
  EXPECT_EQ(DownsampleFactor(4097, 4096), 2);
  EXPECT_EQ(DownsampleFactor(1, 4096), 1);
}

TEST(MapDownsample, BlockMeansSkipUncoveredAndMissingCells) {
  const PipeMaps m = RandomMaps(37, 50, 1);
  MapDownsampler down({0, 37, 0, 50}, 50, 4, 3);
  down.Add(m, 0);
  const CoarseMaps out = down.Finish();
  ASSERT_EQ(out.displacement_mm.rows, 10);                         // ceil(37 / 4)
  ASSERT_EQ(out.displacement_mm.cols, 17);                         // ceil(50 / 3)
  for (const auto& [i, j] : {std::pair{0, 0}, {4, 7}, {9, 16}}) {  // the last: a partial block
    double sum = 0.0, colour = 0.0;
    int n = 0, cells = 0;
    for (int r = 4 * i; r < std::min(37, 4 * i + 4); ++r) {
      for (int c = 3 * j; c < std::min(50, 3 * j + 3); ++c) {
        ++cells;
        if (m.coverage(r, c) == 0) continue;
        sum += m.displacement_mm(r, c);
        colour += m.texture(r, c)[1];
        ++n;
      }
    }
    ASSERT_GT(n, 0);
    EXPECT_NEAR(out.displacement_mm(i, j), sum / n, 1e-5);
    EXPECT_NEAR(out.texture(i, j)[1], colour / n, 0.5 + 1e-6);
    EXPECT_NEAR(out.coverage(i, j), static_cast<double>(n) / cells, 1e-6);
  }
}

TEST(MapDownsample, TilesGiveTheSameAsTheWholeMaps) {
  const PipeMaps m = RandomMaps(64, 40, 2);
  MapDownsampler whole({5, 50, 0, 40}, 40, 3, 4), tiled({5, 50, 0, 40}, 40, 3, 4);
  whole.Add(m, 0);
  tiled.Add(Rows(m, 40, 24), 40);  // any order; rows outside the region ignored
  tiled.Add(Rows(m, 0, 17), 0);
  tiled.Add(Rows(m, 17, 23), 17);
  const CoarseMaps a = whole.Finish(), b = tiled.Finish();
  EXPECT_EQ(cv::norm(a.texture, b.texture, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.coverage, b.coverage, cv::NORM_INF), 0.0);
  cv::Mat1f da = a.displacement_mm.clone(), db = b.displacement_mm.clone();
  cv::patchNaNs(da, -99.0);
  cv::patchNaNs(db, -99.0);
  EXPECT_LT(cv::norm(da, db, cv::NORM_INF), 1e-5);
}

TEST(MapDownsample, RegionWrapsAroundTheClock) {
  const PipeMaps m = RandomMaps(4, 10, 3);
  MapDownsampler down({1, 2, 8, 4}, 10, 1, 1);  // columns 8, 9, 0, 1
  down.Add(m, 0);
  const CoarseMaps out = down.Finish();
  for (int j = 0; j < 4; ++j) {
    const int col = (8 + j) % 10;
    for (int i = 0; i < 2; ++i) {
      if (m.coverage(1 + i, col) == 0) {
        EXPECT_TRUE(std::isnan(out.displacement_mm(i, j)));
      } else {
        EXPECT_EQ(out.displacement_mm(i, j), m.displacement_mm(1 + i, col));
        EXPECT_EQ(out.texture(i, j), m.texture(1 + i, col));
      }
    }
  }
}

}  // namespace
}  // namespace sewer3d
