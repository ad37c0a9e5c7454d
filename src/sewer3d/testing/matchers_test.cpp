#include "sewer3d/testing/matchers.hpp"

#include <gtest/gtest.h>

#include "sewer3d/testing/small_module.hpp"

namespace sewer3d::testing {
namespace {

TEST(PoseNear, AcceptsWithinAndRejectsBeyondEachTolerance) {
  const Rigid3d a(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1, 2, 3));
  const Rigid3d turned(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * kRadPerDeg, Eigen::Vector3d::UnitZ())),
      Eigen::Vector3d(1, 2, 3.2));
  EXPECT_NEAR(RotationErrorDeg(a, turned), 0.5, 1e-9);
  EXPECT_NEAR(TranslationErrorMm(a, turned), 0.2, 1e-12);
  EXPECT_THAT(turned, PoseNear(a, 0.51, 0.21));
  EXPECT_THAT(turned, ::testing::Not(PoseNear(a, 0.49, 0.21)));
  EXPECT_THAT(turned, ::testing::Not(PoseNear(a, 0.51, 0.19)));
}

TEST(SmallDefaultModule, SameAnglesAtAQuarterOfTheSize) {
  const ModuleDescription small = SmallDefaultModule(648), full = MakeDefaultModule({});
  EXPECT_EQ(small.camera.width, 648);
  EXPECT_EQ(small.camera.height, 486);
  EXPECT_NEAR(small.camera.fx * 4.0, full.camera.fx, 1e-6 * full.camera.fx);
}

}  // namespace
}  // namespace sewer3d::testing
