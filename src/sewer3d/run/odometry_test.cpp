#include "sewer3d/run/odometry.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace sewer3d {
namespace {

// 20 Hz at 100 mm/s from line 2 (line 1 is the header), plus `noise` on every other reading.
std::vector<OdometryReading> Steady(int n, double noise = 0.0) {
  std::vector<OdometryReading> r;
  for (int i = 0; i < n; ++i) r.push_back({0.05 * i, 5.0 * i + (i % 2 ? noise : -noise), i + 2});
  return r;
}

TEST(OdometryDistanceAt, LinearBetweenReadingsNothingOutside) {
  const std::vector<OdometryReading> r = {{0.0, 0.0}, {0.05, 5.0}, {0.10, 9.0}};
  EXPECT_DOUBLE_EQ(*OdometryDistanceAt(r, 0.0), 0.0);
  EXPECT_NEAR(*OdometryDistanceAt(r, 0.025), 2.5, 1e-12);
  EXPECT_NEAR(*OdometryDistanceAt(r, 0.075), 7.0, 1e-12);
  EXPECT_DOUBLE_EQ(*OdometryDistanceAt(r, 0.10), 9.0);
  EXPECT_FALSE(OdometryDistanceAt(r, -0.001));
  EXPECT_FALSE(OdometryDistanceAt(r, 0.101));
  EXPECT_FALSE(OdometryDistanceAt({}, 0.0));
}

TEST(CheckOdometry, KeepsASteadyCounterWithNoise) {
  // A standing robot's counter jitters back and forth by the reading noise: not a reversal.
  std::vector<OdometryReading> r = Steady(10, 0.8);
  for (int i = 10; i < 20; ++i) r.push_back({0.05 * i, 45.0 + (i % 2 ? 0.7 : -0.7), i + 2});
  const OdometryCheck c = CheckOdometry(r);
  EXPECT_EQ(c.kept.size(), r.size());
  EXPECT_TRUE(c.findings.reversals.empty());
  EXPECT_TRUE(c.findings.gaps.empty());
  EXPECT_EQ(OdometryUncertaintyAt(c.findings, 0.33).sigma_mm, 0.0);
}

// Distances in micrometres (or metres read as mm × 1000): 100 m/s, no crawler moves so fast.
TEST(CheckOdometry, RefusesACounterFasterThanACrawler) {
  std::vector<OdometryReading> r = Steady(20);
  EXPECT_NO_THROW(CheckOdometry(r));  // 100 mm/s
  for (OdometryReading& reading : r) reading.distance_mm *= 1000.0;
  try {
    CheckOdometry(r);
    ADD_FAILURE() << "100 m/s accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("is distance_mm in millimetres?"), std::string::npos)
        << e.what();
  }
}

TEST(CheckOdometry, DropsReadingsGoingBackwardsAndNamesTheirLines) {
  std::vector<OdometryReading> r = Steady(20);
  for (int i = 9; i <= 12; ++i) r[i].distance_mm -= 60.0;  // lines 11..14
  r[15].distance_mm -= 8.0;  // line 17: 3 mm below line 16's, beyond the 2 mm tolerance
  const OdometryCheck c = CheckOdometry(r);
  ASSERT_EQ(c.findings.reversals.size(), 2u);
  const OdometryReversal& first = c.findings.reversals[0];
  EXPECT_EQ(first.first_line, 11);
  EXPECT_EQ(first.last_line, 14);
  EXPECT_EQ(first.readings, 4);
  EXPECT_DOUBLE_EQ(first.before_mm, 40.0);
  EXPECT_DOUBLE_EQ(first.lowest_mm, 45.0 - 60.0);
  EXPECT_EQ(c.findings.reversals[1].first_line, 17);
  EXPECT_EQ(c.findings.reversals[1].last_line, 17);
  EXPECT_EQ(c.kept.size(), 15u);
  // Lines 10 and 15 (0.40 s, 0.65 s) now bound the only gap longer than 0.2 s.
  ASSERT_EQ(c.findings.gaps.size(), 1u);
  EXPECT_DOUBLE_EQ(c.findings.gaps[0].from_s, 0.40);
  EXPECT_DOUBLE_EQ(c.findings.gaps[0].to_s, 0.05 * 13);
  EXPECT_EQ(c.findings.gaps[0].from_line, 10);
  EXPECT_EQ(c.findings.gaps[0].to_line, 15);
  // Interpolated across: the true 50 mm at 0.5 s, as a guess of σ = 100 mm/s · 0.1 · 0.15 / 0.25.
  EXPECT_NEAR(*OdometryDistanceAt(c.kept, 0.5), 50.0, 1e-9);
  const OdometryUncertainty u = OdometryUncertaintyAt(c.findings, 0.5);
  EXPECT_NEAR(u.sigma_mm, 6.0, 1e-9);
  EXPECT_EQ(u.speed_sigma_mm_s, 100.0);
  EXPECT_EQ(u.gap, &c.findings.gaps[0]);
  EXPECT_EQ(OdometryUncertaintyAt(c.findings, 0.35).gap, nullptr);
}

TEST(CheckOdometry, ListsGapsLongerThanTheBound) {
  std::vector<OdometryReading> r = Steady(30);
  r.erase(r.begin() + 5, r.begin() + 7);    // 0.15 s from line 6 to line 9: interpolated
  r.erase(r.begin() + 12, r.begin() + 25);  // 0.70 s: flagged
  const OdometryCheck c = CheckOdometry(r);
  EXPECT_TRUE(c.findings.reversals.empty());
  ASSERT_EQ(c.findings.gaps.size(), 1u);
  EXPECT_NEAR(c.findings.gaps[0].to_s - c.findings.gaps[0].from_s, 0.70, 1e-9);
  EXPECT_EQ(OdometryUncertaintyAt(c.findings, 0.3).sigma_mm, 0.0);
  EXPECT_NEAR(OdometryUncertaintyAt(c.findings, 1.0).sigma_mm, 100.0 * 0.35 * 0.35 / 0.7, 1e-9);
}

TEST(CheckOdometry, RejectsBadOptionsAndUnsortedReadings) {
  OdometryCheckOptions o;
  o.max_gap_s = 0.0;
  EXPECT_THROW(CheckOdometry(Steady(3), o), std::invalid_argument);
  std::vector<OdometryReading> r = Steady(3);
  r[2].time_s = r[1].time_s;
  EXPECT_THROW(CheckOdometry(r), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
