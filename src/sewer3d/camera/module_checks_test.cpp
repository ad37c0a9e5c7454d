#include "sewer3d/camera/module_checks.hpp"

#include <gtest/gtest.h>

#include "sewer3d/camera/default_module.hpp"

namespace sewer3d {
namespace {

using Cause = UsabilityProblem::Cause;

// The shipped pattern: 6 x 200 elements read in 6 x 6 windows.
std::optional<UsabilityProblem> Problem(const DefaultModuleOptions& options, int cols = 200) {
  return FindUsabilityProblem(MakeDefaultModule(options), 6, cols, 6);
}

DefaultModuleOptions Reduced() {
  DefaultModuleOptions options;
  options.camera_width = 648;
  options.camera_height = 486;
  return options;
}

TEST(FindUsabilityProblem, DefaultModulesAreUsable) {
  EXPECT_FALSE(Problem(DefaultModuleOptions{}).has_value());
  EXPECT_FALSE(Problem(Reduced()).has_value());
  // Full size: f ≈ 1660 px, baseline ≈ 75 mm: z² σ / (f b) at 225 mm ≈ 0.04 mm.
  EXPECT_NEAR(DepthErrorMm(MakeDefaultModule(DefaultModuleOptions{}), 225.0), 0.04, 0.02);
}

TEST(FindUsabilityProblem, NamesEachCause) {
  auto options = Reduced();
  options.stereo_angle_deg = 1.0;  // a 2.6 mm baseline: ±4.5 mm at 225 mm
  auto problem = Problem(options);
  ASSERT_TRUE(problem.has_value());
  EXPECT_EQ(problem->cause, Cause::kDepthPrecision);
  EXPECT_NE(problem->text.find("depth error"), std::string::npos) << problem->text;

  options = Reduced();
  options.pitch_px = 2.0;  // a quarter of the camera's scale: 0.5 px pitch on the sensor
  options.spot_diameter_px = 0.5;
  problem = Problem(options);
  ASSERT_TRUE(problem.has_value());
  EXPECT_EQ(problem->cause, Cause::kSpotSize);

  options = Reduced();
  options.pitch_px = 100.0;  // 600 px windows on a 648 x 486 projector
  options.spot_diameter_px = 50.0;
  problem = Problem(options);
  ASSERT_TRUE(problem.has_value());
  EXPECT_EQ(problem->cause, Cause::kWindowFit);

  // The projector moved to the camera's other side, still turned as before: its field leaves
  // the camera's (a rendered plane at 140 mm decodes 0 spots).
  ModuleDescription flipped = MakeDefaultModule(Reduced());
  flipped.projector_from_camera.translation.x() *= -1.0;
  problem = FindUsabilityProblem(flipped, 6, 200, 6);
  ASSERT_TRUE(problem.has_value());
  EXPECT_EQ(problem->cause, Cause::kFieldOverlap);
  EXPECT_LT(LitShare(flipped, 150.0), 0.2);
  EXPECT_GT(LitShare(MakeDefaultModule(Reduced()), 150.0), 0.8);

  problem = Problem(Reduced(), 8);  // eight columns cannot span the disparity range
  ASSERT_TRUE(problem.has_value());
  EXPECT_EQ(problem->cause, Cause::kPatternSpan);
  EXPECT_NE(problem->text.find("8 columns"), std::string::npos) << problem->text;
}

}  // namespace
}  // namespace sewer3d
