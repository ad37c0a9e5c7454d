#include "sewer3d/sim/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"

namespace sewer3d {
namespace {

TEST(Scene, TiltedPlaneMatchesClosedForm) {
  Scene s;
  s.distance_mm = 90.0;
  s.tilt_deg = 20.0;
  for (double y : {-0.5, 0.0, 0.3, 0.7}) {
    const auto hit = Intersect(s, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.2, y, 1.0));
    ASSERT_TRUE(hit.has_value());
    // Plane z = d + y_world tan(tilt): along the ray t = d / (1 − y tan(tilt)).
    EXPECT_NEAR(hit->point.z(), 90.0 / (1.0 - y * std::tan(DegToRad(20.0))), 1e-9);
    EXPECT_NEAR(hit->normal.norm(), 1.0, 1e-12);
    EXPECT_LT(hit->normal.z(), 0.0);  // faces the camera
  }
}

TEST(Scene, DecentredCylinderMatchesClosedForm) {
  Scene s;
  s.type = Scene::Type::kCylinder;
  s.diameter_mm = 300.0;
  s.axis_point_mm = {10.0, 0.0, 20.0};  // camera 22 mm off the axis
  for (double x : {-0.7, 0.0, 0.4}) {
    const auto hit = Intersect(s, Eigen::Vector3d::Zero(), Eigen::Vector3d(x, 0.3, 1.0));
    ASSERT_TRUE(hit.has_value());
    // (t x − 10)² + (t − 20)² = 150², far root.
    const double a = x * x + 1, b = -2 * (10 * x + 20), c = 100 + 400 - 22500;
    const double t = (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
    EXPECT_NEAR(hit->point.z(), t, 1e-9);
    EXPECT_NEAR(std::hypot(hit->point.x() - 10.0, hit->point.z() - 20.0), 150.0, 1e-9);
  }
}

TEST(Scene, PipeWallFollowsItsDisplacementField) {
  Scene s;
  s.type = Scene::Type::kPipeWall;
  s.diameter_mm = 300.0;
  s.features = {{.type = PipeFeature::Type::kJointStep,
                 .station_mm = 0.0,
                 .clock_h = 0.0,
                 .depth_mm = 3.0,
                 .gap_mm = 4.0,
                 .offset_mm = 5.0},
                {.type = PipeFeature::Type::kBump,
                 .station_mm = -40.0,
                 .clock_h = 0.0,
                 .height_mm = 8.0,
                 .radius_mm = 6.0}};
  // Beyond the joint at clock 0 the wall is 5 mm closer; in the gap 3 mm deeper; on the bump
  // top 8 mm closer.
  auto radius_at = [&](double y) {
    const auto hit = Intersect(s, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, y, 1.0));
    EXPECT_TRUE(hit.has_value());
    return std::hypot(hit->point.x(), hit->point.z());
  };
  EXPECT_NEAR(radius_at(0.3), 145.0, 1e-6);            // station ~ +45 mm
  EXPECT_NEAR(radius_at(-0.07), 150.0, 1e-3);          // station ~ −10 mm, plain wall
  EXPECT_NEAR(radius_at(0.0), 153.0, 1e-6);            // in the gap
  EXPECT_NEAR(radius_at(-40.0 / 142.0), 142.0, 0.05);  // bump top (station −40)
  EXPECT_NEAR(WallDisplacementMm(s, 0.0, -40.0), 8.0, 1e-12);
}

TEST(Scene, RejectsCameraOutsideCylinder) {
  Scene s;
  s.type = Scene::Type::kCylinder;
  s.diameter_mm = 100.0;
  s.axis_point_mm = {0.0, 0.0, 80.0};
  EXPECT_THROW(s.Check(), std::invalid_argument);
}

TEST(Scene, TakesTheWallFeaturesItCanRender) {
  Scene s;
  s.type = Scene::Type::kPipeWall;
  s.features = {{.type = PipeFeature::Type::kCrack, .length_mm = 20.0, .width_mm = 1.0}};
  try {
    s.Check();
    FAIL() << "a crack without depth passed";
  } catch (const InvalidValue& e) {
    EXPECT_EQ(e.field(), "features[0].depth_mm");
  }
  s.features[0].depth_mm = 1.0;
  EXPECT_NO_THROW(s.Check());
  // A wet patch: the same wall, wetted where it lies.
  s.diameter_mm = 300.0;
  s.features.push_back({.type = PipeFeature::Type::kWet, .length_mm = 40.0, .width_mm = 40.0});
  EXPECT_NO_THROW(s.Check());
  const auto wet = Intersect(s, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.05, 0.0, 1.0));
  const auto dry = Intersect(s, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.5, 1.0));
  ASSERT_TRUE(wet && dry);
  EXPECT_EQ(wet->film, 1.0);
  EXPECT_EQ(dry->film, 0.0);
  EXPECT_NEAR(wet->point.norm(), 150.0, 1e-6);  // beside the crack: no shape of its own
  s.features.pop_back();
  s.features.push_back({.type = PipeFeature::Type::kDeposit, .length_mm = 50.0, .height_mm = 5.0});
  try {
    s.Check();
    FAIL() << "a deposit passed";
  } catch (const InvalidValue& e) {
    EXPECT_EQ(e.field(), "features[1].type");
  }
}

TEST(Scene, JointStepsAreHeldToOneJointsLimitTogether) {
  Scene s;
  s.type = Scene::Type::kPipeWall;
  s.diameter_mm = 300.0;
  const PipeFeature joint{
      .type = PipeFeature::Type::kJointStep, .depth_mm = 4.0, .gap_mm = 6.0, .offset_mm = 5.0};
  s.features.assign(12, joint);  // 60 mm: a fifth of the diameter
  EXPECT_NO_THROW(s.Check());
  s.features.push_back(joint);
  try {
    s.Check();
    FAIL() << "13 joints of 5 mm in a Ø300 wall passed";
  } catch (const InvalidValue& e) {
    EXPECT_EQ(e.field(), "features");
  }
}

}  // namespace
}  // namespace sewer3d
