#include "sewer3d/model/map_accumulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "sewer3d/model/axis_curve.hpp"
#include "sewer3d/model/unroll.hpp"

namespace sewer3d {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRadius = 50.0;  // a small pipe keeps the grids small: 1571 columns at 0.2 mm

// A straight, offset and slightly tilted centreline of model radius kRadius.
Centreline TestCentreline() {
  const Eigen::Vector3d p0(3.0, -2.0, 0.0), t = Eigen::Vector3d(0.01, -0.02, 1.0).normalized();
  auto line = ResampleAxis({p0 - 50.0 * t, p0 + 100.0 * t}, 10.0);
  EXPECT_TRUE(line.has_value());
  line->radius_mm = kRadius;
  return *line;
}

// The cell centre's (station, clock) of `grid`.
CylPoint CellCentre(const MapGrid& grid, int r, int c, double radius) {
  return {grid.RowStationMm(r), grid.ColClockRad(c), radius};
}

double Bump(double station, double clock) {
  const double arc = kRadius * std::remainder(clock - 1.0, 2 * kPi);
  return 3.0 * std::exp(-(std::pow(station - 20.0, 2) + arc * arc) / (2 * 16.0));
}

TEST(MapAccumulator, RecoversABumpAndColourFromDenseNoisySamples) {
  const Centreline line = TestCentreline();
  const MapGrid grid = MakeMapGrid(0.0, 40.0, kRadius, 0.2);
  MapAccumulator acc(line, grid, {});
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.02), colour_noise(0.0, 4.0);
  std::uniform_real_distribution<double> jitter(0.0, 1.0);
  const double spacing = 0.1;  // dense per-pixel samples: ~4 per cell
  const int n_clock = static_cast<int>(2 * kPi * kRadius / spacing);
  for (double s = 0.0; s < 40.0; s += spacing) {
    for (int k = 0; k < n_clock; ++k) {
      const double st = s + spacing * jitter(rng), clock = (k + jitter(rng)) * 2 * kPi / n_clock;
      const double radius = kRadius + Bump(st, clock) + noise(rng);
      const cv::Vec3f bgr(static_cast<float>(120 + 60 * std::sin(clock) + colour_noise(rng)), 80.f,
                          static_cast<float>(30 + 2 * st));
      ASSERT_TRUE(
          acc.Add(PointAt(line, {st, clock, radius}), bgr, DepthWeight(150.0, 0.05, 150.0)));
    }
  }
  const PipeMaps maps = acc.Finish();
  ASSERT_EQ(maps.displacement_mm.rows, 200);
  ASSERT_EQ(maps.displacement_mm.cols, 1571);
  double sum2 = 0.0, worst = 0.0, peak = 0.0, colour_worst = 0.0;
  int measured = 0;
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      ASSERT_NE(maps.coverage(r, c), static_cast<unsigned char>(Coverage::kNone));
      measured += maps.coverage(r, c) == static_cast<unsigned char>(Coverage::kMeasured);
      const CylPoint cell = CellCentre(grid, r, c, kRadius);
      const double e = maps.displacement_mm(r, c) - Bump(cell.station_mm, cell.clock_rad);
      sum2 += e * e, worst = std::max(worst, std::abs(e));
      peak = std::max(peak, static_cast<double>(maps.displacement_mm(r, c)));
      colour_worst =
          std::max(colour_worst, std::abs(maps.texture(r, c)[2] - (30 + 2 * cell.station_mm)));
    }
  }
  const double rms = std::sqrt(sum2 / (grid.rows * grid.cols));
  // ~4 samples per cell of σ 0.02 mm: σ of a mean ≈ 0.01 mm (cells with fewer samples more).
  EXPECT_LT(rms, 0.015);
  EXPECT_LT(worst, 0.08);
  EXPECT_NEAR(peak, 3.0, 0.04);
  EXPECT_GT(measured, 0.97 * grid.rows * grid.cols);
  EXPECT_LE(colour_worst, 1.0);  // a ramp of 0.4 per cell, rounded
  std::printf("bump: rms %.4f mm, worst %.4f mm, peak %.4f mm, measured %.4f\n", rms, worst, peak,
              static_cast<double>(measured) / (grid.rows * grid.cols));
}

// One sample at the centre of each cell of `grid` unless `skip` says so.
template <typename Skip, typename Value>
void FeedCellCentres(MapAccumulator& acc, const Centreline& line, const MapGrid& grid, Skip skip,
                     Value value, double weight) {
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      if (skip(r, c)) continue;
      const CylPoint cell = CellCentre(grid, r, c, kRadius);
      const auto [displacement, bgr] = value(cell);
      acc.Add(PointAt(line, {cell.station_mm, cell.clock_rad, kRadius + displacement}), bgr,
              weight);
    }
  }
}

TEST(MapAccumulator, BlendsOverlappingModulesByWeight) {
  const Centreline line = TestCentreline();
  const MapGrid grid = MakeMapGrid(0.0, 4.0, kRadius, 0.2);
  MapAccumulator acc(line, grid, {});
  auto a = [](const CylPoint&) { return std::pair{0.1, cv::Vec3f(100, 100, 100)}; };
  auto b = [](const CylPoint&) { return std::pair{-0.1, cv::Vec3f(200, 0, 60)}; };
  const int split_a = grid.cols * 6 / 10, split_b = grid.cols / 2;
  FeedCellCentres(
      acc, line, grid, [&](int, int c) { return c >= split_a; }, a, 1.0);
  FeedCellCentres(
      acc, line, grid, [&](int, int c) { return c < split_b; }, b, 3.0);
  const PipeMaps maps = acc.Finish();
  for (int r = 0; r < grid.rows; ++r) {
    EXPECT_NEAR(maps.displacement_mm(r, 10), 0.1, 1e-6);
    EXPECT_EQ(maps.texture(r, 10), cv::Vec3b(100, 100, 100));
    EXPECT_EQ(maps.samples(r, 10), 1);
    const int overlap = (split_a + split_b) / 2;
    EXPECT_NEAR(maps.displacement_mm(r, overlap), (0.1 - 0.3) / 4, 1e-6);
    EXPECT_EQ(maps.texture(r, overlap), cv::Vec3b(175, 25, 70));
    EXPECT_EQ(maps.samples(r, overlap), 2);
    EXPECT_NEAR(maps.displacement_mm(r, grid.cols - 1), -0.1, 1e-6);
  }
}

TEST(MapAccumulator, FillsSmallHolesOnlyAcrossTheClockSeamToo) {
  const Centreline line = TestCentreline();
  const MapGrid grid = MakeMapGrid(0.0, 20.0, kRadius, 0.2);
  MapAccumulator acc(line, grid, {});  // holes up to 2 mm = 10 cells
  const int cols = grid.cols;
  auto in_small = [&](int r, int c) { return r >= 20 && r < 26 && c >= 300 && c < 306; };
  auto in_seam = [&](int r, int c) { return r >= 40 && r < 45 && (c >= cols - 3 || c < 4); };
  auto in_large = [&](int r, int c) { return r >= 60 && r < 85 && c >= 600 && c < 625; };
  auto linear = [](const CylPoint& p) {
    return std::pair{0.05 * p.station_mm, cv::Vec3f(static_cast<float>(5 * p.station_mm), 50, 9)};
  };
  FeedCellCentres(
      acc, line, grid,
      [&](int r, int c) { return in_small(r, c) || in_seam(r, c) || in_large(r, c); }, linear, 1.0);
  const PipeMaps maps = acc.Finish();
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const auto coverage = static_cast<Coverage>(maps.coverage(r, c));
      if (in_large(r, c)) {
        EXPECT_EQ(coverage, Coverage::kNone);
        EXPECT_TRUE(std::isnan(maps.displacement_mm(r, c)));
        EXPECT_EQ(maps.texture(r, c), cv::Vec3b(0, 0, 0));
        continue;
      }
      EXPECT_EQ(coverage,
                in_small(r, c) || in_seam(r, c) ? Coverage::kFilled : Coverage::kMeasured);
      EXPECT_NEAR(maps.displacement_mm(r, c), 0.05 * grid.RowStationMm(r), 1e-5);  // linear: exact
      EXPECT_NEAR(maps.texture(r, c)[0], 5 * grid.RowStationMm(r), 0.5 + 1e-3);
    }
  }
}

TEST(MapAccumulator, TilesSideBySideEqualOneGrid) {
  const Centreline line = TestCentreline();
  const MapGrid grid = MakeMapGrid(0.0, 30.0, kRadius, 0.2);
  MapAccumulatorOptions options;
  options.splat_radius_mm = 0.9;  // sparse random points, ~0.6 mm apart
  MapAccumulator whole(line, grid, options), first(line, grid.Tile(0, 70), options),
      second(line, grid.Tile(70, 80), options);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> station(-2.0, 32.0), clock(0.0, 2 * kPi);
  for (int i = 0; i < 30000; ++i) {
    const double s = station(rng), t = clock(rng);
    const double arc = kRadius * t;
    if (std::abs(s - 14.0) < 0.9 && std::abs(arc - 40.0) < 0.9) continue;  // small hole, boundary
    if (std::abs(s - 14.0) < 4.0 && std::abs(arc - 90.0) < 4.0) continue;  // large hole, boundary
    const double radius = kRadius + Bump(s, t);
    const Eigen::Vector3d p = PointAt(line, {s, t, radius});
    const cv::Vec3f bgr(static_cast<float>(100 + 20 * std::cos(3 * t)), 60, 70);
    whole.Add(p, bgr, 1.0), first.Add(p, bgr, 1.0), second.Add(p, bgr, 1.0);
  }
  const PipeMaps all = whole.Finish(), a = first.Finish(), b = second.Finish();
  int filled = 0, none = 0, mismatches = 0;
  for (int r = 0; r < grid.rows; ++r) {
    const PipeMaps& tile = r < 70 ? a : b;
    const int tr = r < 70 ? r : r - 70;
    for (int c = 0; c < grid.cols; ++c) {
      filled += all.coverage(r, c) == static_cast<unsigned char>(Coverage::kFilled);
      none += all.coverage(r, c) == static_cast<unsigned char>(Coverage::kNone);
      const float d0 = all.displacement_mm(r, c), d1 = tile.displacement_mm(tr, c);
      const bool same = all.coverage(r, c) == tile.coverage(tr, c) &&
                        all.samples(r, c) == tile.samples(tr, c) &&
                        all.texture(r, c) == tile.texture(tr, c) &&
                        ((std::isnan(d0) && std::isnan(d1)) || std::abs(d0 - d1) < 1e-5);
      mismatches += same ? 0 : 1;
    }
  }
  EXPECT_EQ(mismatches, 0);
  auto at = [&](double station, double arc) {
    return static_cast<Coverage>(all.coverage(
        static_cast<int>(station / 0.2), static_cast<int>(arc / kRadius / (2 * kPi) * grid.cols)));
  };
  EXPECT_EQ(at(14.0, 40.0), Coverage::kFilled);  // the small hole on the tiles' boundary
  EXPECT_EQ(at(14.0, 90.0), Coverage::kNone);    // the large hole on it
  EXPECT_EQ(at(12.0, 88.0), Coverage::kNone);
  EXPECT_LT(none, 40 * 40);  // just the large hole (8 mm square less the splat reach)
  std::printf("tiles: filled %d, none %d of %d cells\n", filled, none, grid.rows * grid.cols);
}

TEST(MapAccumulator, WeightsAndOptions) {
  EXPECT_NEAR(DepthWeight(300.0, 0.05, 150.0), 1.0 / std::pow(0.2, 2), 1e-9);
  EXPECT_NEAR(BorderFeather(10.0, 500.0, 2592, 1944, 100.0), 0.105, 1e-12);
  EXPECT_EQ(BorderFeather(1296.0, 972.0, 2592, 1944, 100.0), 1.0);
  MapAccumulatorOptions bad;
  bad.max_hole_mm = -1.0;
  EXPECT_THROW(bad.Check(), std::invalid_argument);
}

// Frames see a gap 8 mm wide (stations 16–24) each with its own edges, off by −1.6 … +1.6 mm
// on either side as the midpoint-drawn holes of frames whose spots fall differently are: the
// union of their surfaces leaves a hole 3.2 mm too narrow, the frames' median edge
// (hole_edge_band_mm, each frame's hole marked seen) the true width — with five frames, and
// with four, where cells between the middle two edges are ties split halfway; and with one
// more frame that measures the wall a little beyond the gap but does not see the gap.
TEST(MapAccumulator, PutsHoleEdgesAtTheFramesMedian) {
  const Centreline line = TestCentreline();
  const MapGrid grid = MakeMapGrid(0.0, 40.0, kRadius, 0.2);
  const auto hole_mm = [&](double band_mm, int frames, bool beyond = false) {
    MapAccumulator acc(line, grid, {.hole_edge_band_mm = band_mm});
    const double before[5] = {-1.6, 0.8, 1.6, -0.8, 0.0}, after[5] = {0.8, -1.6, 1.6, -0.8, 0.0};
    const auto frame = [&](double from, double gap_begin, double gap_end) {
      acc.BeginFrame();
      for (double s = from + 0.05; s < 40.0; s += 0.15) {
        for (double clock = 0.0; clock < 2 * kPi; clock += 0.15 / kRadius) {
          const Eigen::Vector3d p = PointAt(line, {s, clock, kRadius});
          if (s > gap_begin && s < gap_end) {
            acc.AddSeen(p);
          } else {
            acc.Add(p, cv::Vec3f(100.f, 100.f, 100.f), 1.0);
          }
        }
      }
    };
    for (int f = 0; f < frames; ++f) frame(0.0, 16.0 + before[f], 24.0 + after[f]);
    if (beyond) frame(28.0, 0.0, 0.0);
    const PipeMaps maps = acc.Finish();
    double rows = 0.0;  // mean over the columns of the empty rows
    for (int c = 0; c < maps.coverage.cols; ++c)
      for (int r = 0; r < maps.coverage.rows; ++r) rows += maps.coverage(r, c) == 0 ? 1 : 0;
    return rows / maps.coverage.cols * grid.resolution_mm;
  };
  EXPECT_NEAR(hole_mm(0.0, 5), 8.0 - 3.2, 0.25);  // the farthest frame on each side
  EXPECT_NEAR(hole_mm(5.0, 5), 8.0, 0.25);        // the median on each side
  EXPECT_NEAR(hole_mm(0.0, 4), 8.0 - 3.2, 0.25);
  EXPECT_NEAR(hole_mm(5.0, 4), 8.0, 0.25);  // halfway between the middle two
  // Were the bar the most frames measuring a cell within the band (as before session 46),
  // the sixth frame would move the far edge out, halfway to where four of the five reach: 8.4.
  EXPECT_NEAR(hole_mm(5.0, 5, true), 8.0, 0.25);
}

}  // namespace
}  // namespace sewer3d
