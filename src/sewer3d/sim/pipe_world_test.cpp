#include "sewer3d/sim/pipe_world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"

namespace sewer3d {
namespace {

PipeWorld TwoSections(const PipeJoint& joint) {
  PipeWorld w;
  w.sections = {{.length_mm = 1000.0, .diameter_mm = 300.0},
                {.length_mm = 1000.0, .diameter_mm = 300.0}};
  w.joints = {joint};
  return w;
}

// Distance from a world point to the wall along a clock direction of section 0's frame.
double WallDistance(const PipeGeometry& pipe, double station, double clock_h) {
  const Eigen::Vector3d o(0.0, 0.0, station);
  const auto hit = pipe.Intersect(o, ClockDirection(ClockHoursToRad(clock_h)));
  EXPECT_TRUE(hit.has_value());
  return hit ? (hit->point - o).norm() : NAN;
}

TEST(PipeWorld, StraightPipeIsACylinder) {
  PipeWorld w;
  w.sections = {{.length_mm = 1000.0, .diameter_mm = 300.0}};
  const PipeGeometry pipe(w);
  for (double clock = 0.5; clock < 12.0; clock += 1.7) {
    EXPECT_NEAR(WallDistance(pipe, 400.0, clock), 150.0, 1e-6);
  }
  // An oblique ray from an off-axis point.
  const Eigen::Vector3d o(10.0, 20.0, 300.0), d(0.3, -0.8, 0.5);
  const auto hit = pipe.Intersect(o, d);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(std::hypot(hit->point.x(), hit->point.y()), 150.0, 1e-6);
  EXPECT_NEAR(hit->t * d.norm(), (hit->point - o).norm(), 1e-9);
  EXPECT_LT(hit->normal.dot(d), 0.0);
  const PipeLocation at = pipe.Locate(hit->point);
  EXPECT_NEAR(at.station_mm, hit->point.z(), 1e-9);
  EXPECT_NEAR(at.clock_rad, std::atan2(hit->point.x(), -hit->point.y()), 1e-9);
  EXPECT_EQ(hit->material, Material::kConcrete);
}

TEST(PipeWorld, JointOffsetMovesTheNextSection) {
  PipeJoint j;
  j.gap_mm = 10.0;
  j.gap_depth_mm = 4.0;
  j.offset_mm = 5.0;
  j.offset_clock_h = 12.0;
  const PipeGeometry pipe(TwoSections(j));
  EXPECT_NEAR(WallDistance(pipe, 900.0, 12.0), 150.0, 1e-6);
  EXPECT_NEAR(WallDistance(pipe, 1100.0, 12.0), 145.0, 1e-6);  // inward at the offset's clock
  EXPECT_NEAR(WallDistance(pipe, 1100.0, 6.0), 155.0, 1e-6);
  EXPECT_NEAR(WallDistance(pipe, 1100.0, 3.0), std::sqrt(150.0 * 150.0 - 25.0), 1e-6);
  EXPECT_NEAR(WallDistance(pipe, 998.0, 3.0), 154.0, 1e-6);  // in the open gap
}

TEST(PipeWorld, DeflectionTurnsTheAxis) {
  PipeJoint j;
  j.deflection_deg = 2.0;
  j.deflection_clock_h = 3.0;
  const PipeGeometry pipe(TwoSections(j));
  const Rigid3d f = pipe.SectionFrame(1, 800.0);
  EXPECT_NEAR(f.translation.x(), 800.0 * std::sin(DegToRad(2.0)), 1e-9);
  EXPECT_NEAR(f.translation.z(), 1000.0 + 800.0 * std::cos(DegToRad(2.0)), 1e-9);
  const Eigen::Vector3d tangent = f.rotation * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(RadToDeg(std::acos(tangent.z())), 2.0, 1e-9);
  // The wall of the second section is a cylinder around its own axis.
  const Eigen::Vector3d p = f * (150.0 * ClockDirection(ClockHoursToRad(4.0)));
  EXPECT_NEAR(pipe.SignedDistanceMm(p), 0.0, 1e-9);
  EXPECT_NEAR(pipe.Locate(p).station_mm, 1800.0, 1e-9);
}

TEST(PipeWorld, GentleBendFollowsAnArc) {
  PipeWorld w;
  w.sections = {
      {.length_mm = 2000.0, .diameter_mm = 300.0, .bend_radius_mm = 10000.0, .bend_clock_h = 3.0}};
  const PipeGeometry pipe(w);
  const double angle = 1500.0 / 10000.0;
  const Rigid3d f = pipe.SectionFrame(0, 1500.0);
  EXPECT_NEAR(f.translation.x(), 10000.0 * (1.0 - std::cos(angle)), 1e-9);
  EXPECT_NEAR(f.translation.z(), 10000.0 * std::sin(angle), 1e-9);
  const Eigen::Vector3d p = f * (120.0 * ClockDirection(ClockHoursToRad(7.0)));
  const PipeLocation at = pipe.Locate(p);
  EXPECT_NEAR(at.station_mm, 1500.0, 1e-9);
  EXPECT_NEAR(at.rho_mm, 120.0, 1e-9);
  EXPECT_NEAR(at.clock_rad, ClockHoursToRad(7.0) - kTwoPi, 1e-9);
  // A ray along the local radial direction meets the wall at the nominal radius.
  const auto hit = pipe.Intersect(f.translation, f.rotation * ClockDirection(ClockHoursToRad(2.0)));
  ASSERT_TRUE(hit);
  EXPECT_NEAR((hit->point - f.translation).norm(), 150.0, 1e-6);
}

TEST(PipeWorld, OvalityChangesTheDiameters) {
  PipeWorld w;
  w.sections = {
      {.length_mm = 1000.0, .diameter_mm = 300.0, .ovality_pct = 5.0, .ovality_clock_h = 12.0}};
  const PipeGeometry pipe(w);
  EXPECT_NEAR(WallDistance(pipe, 500.0, 12.0) + WallDistance(pipe, 500.0, 6.0), 300.0 * 0.95, 1e-5);
  EXPECT_NEAR(WallDistance(pipe, 500.0, 3.0) + WallDistance(pipe, 500.0, 9.0), 300.0 * 1.05, 1e-5);
  EXPECT_NEAR(WallDistance(pipe, 0.0, 12.0), 150.0, 1e-6);  // ramps in from the section ends
}

TEST(PipeWorld, FeaturesDisplaceTheWall) {
  PipeWorld w;
  w.sections = {{.length_mm = 2000.0, .diameter_mm = 300.0}};
  PipeFeature c;
  c.type = PipeFeature::Type::kConnection;
  c.id = "C1";
  c.station_mm = 500.0;
  c.clock_h = 3.0;
  c.diameter_mm = 100.0;
  c.wall_mm = 12.0;
  c.intrusion_mm = 20.0;
  PipeFeature d;
  d.type = PipeFeature::Type::kDeposit;
  d.id = "D1";
  d.station_mm = 1000.0;
  d.clock_h = 6.0;
  d.length_mm = 500.0;
  d.height_mm = 40.0;
  PipeFeature s;
  s.type = PipeFeature::Type::kSpalling;
  s.id = "S1";
  s.station_mm = 1700.0;
  s.clock_h = 12.0;
  s.length_mm = 60.0;
  s.width_mm = 60.0;
  s.depth_mm = 5.0;
  w.features = {c, d, s};
  const PipeGeometry pipe(w);
  EXPECT_NEAR(WallDistance(pipe, 500.0 + 56.0, 3.0), 130.0, 1e-6);  // on the lateral's wall end
  EXPECT_NEAR(WallDistance(pipe, 500.0, 3.0), 150.0 + 50.0, 1e-6);  // down the lateral's bore
  EXPECT_NEAR(WallDistance(pipe, 600.0, 3.0), 150.0, 1e-6);
  // Deposit: flat at the invert, 40 mm high; seen as sediment.
  const double invert = WallDistance(pipe, 1250.0, 6.0);
  EXPECT_NEAR(invert, 110.0, 0.2);  // grit adds ±0.15 mm
  const auto hit = pipe.Intersect({0.0, 0.0, 1250.0}, {0.0, 1.0, 0.0});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->material, Material::kSediment);
  EXPECT_NEAR(WallDistance(pipe, 1250.0, 6.0 + 1.0) * std::cos(DegToRad(30.0)), invert,
              0.3);  // a flat chord
  const double spall = WallDistance(pipe, 1700.0, 12.0);
  EXPECT_GT(spall, 150.0 + 0.6 * 5.0 - 1e-6);
  EXPECT_LT(spall, 150.0 + 1.4 * 5.0 + 1e-6);
}

// A wet patch wets the wall where it lies and leaves its shape alone.
TEST(PipeWorld, AWetPatchWetsTheWallOnly) {
  PipeWorld w;
  w.sections = {{.length_mm = 2000.0, .diameter_mm = 300.0}};
  w.features = {{.type = PipeFeature::Type::kWet,
                 .id = "W1",
                 .station_mm = 800.0,
                 .clock_h = 9.0,
                 .length_mm = 200.0,
                 .width_mm = 150.0}};
  const PipeGeometry pipe(w);
  const auto film = [&](double station, double clock_h) {
    const auto hit = pipe.Intersect({0.0, 0.0, station}, ClockDirection(ClockHoursToRad(clock_h)));
    return hit ? hit->film : -1.0;
  };
  EXPECT_EQ(film(800.0, 9.0), 1.0);
  EXPECT_EQ(film(880.0, 9.5), 1.0);  // 80 of 100 mm along, 39 of 75 mm around
  EXPECT_EQ(film(800.0, 3.0), 0.0);
  EXPECT_EQ(film(1000.0, 9.0), 0.0);
  EXPECT_NEAR(WallDistance(pipe, 800.0, 9.0), 150.0, 1e-6);
  w.features[0].width_mm = 0.0;
  try {
    w.Check();
    FAIL() << "a wet patch without width passed";
  } catch (const InvalidValue& e) {
    EXPECT_EQ(e.field(), "features[0].width_mm");
  }
}

TEST(PipeWorld, PathFrameIsContinuousAcrossJoints) {
  PipeJoint j;
  j.offset_mm = 8.0;
  j.deflection_deg = 3.0;
  const PipeGeometry pipe(TwoSections(j));
  for (double s = 850.0; s < 1150.0; s += 0.5) {
    const Rigid3d a = pipe.PathFrame(s), b = pipe.PathFrame(s + 0.5);
    EXPECT_LT((a.translation - b.translation).norm(), 0.6);
    EXPECT_LT(a.rotation.angularDistance(b.rotation), 0.001);
  }
  EXPECT_LT((pipe.PathFrame(500.0).translation - Eigen::Vector3d(0, 0, 500)).norm(), 1e-9);
}

TEST(PipeWorld, RejectsInconsistentWorlds) {
  PipeWorld w;
  EXPECT_THROW(PipeGeometry{w}, std::invalid_argument);
  w.sections = {{.length_mm = 1000.0}, {.length_mm = 1000.0}};
  EXPECT_THROW(PipeGeometry{w}, std::invalid_argument);  // joint missing
  w.joints.resize(1);
  w.joints[0].offset_mm = 100.0;
  EXPECT_THROW(PipeGeometry{w}, std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
