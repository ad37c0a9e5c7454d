// The simulator's error sources (spot_errors.hpp): each is off by default, deterministic, and
// of the size asked for.

#include "sewer3d/sim/spot_errors.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <utility>

#include "sewer3d/core/units.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

TEST(SpotErrors, IdealIsNoErrorAtAll) {
  const SpotErrors ideal = *RealismProfile("ideal");
  EXPECT_FALSE(ideal.Any());
  EXPECT_EQ(ElementOffset(ideal, 3, 4), Eigen::Vector2d::Zero());
  EXPECT_EQ(ElementGain(ideal, 3, 4), 1.0);
  EXPECT_EQ(WallRelief(ideal, Material::kConcrete, 1, {2.0, 3.0}), 0.0);
  const ModuleDescription m = testing::SmallDefaultModule(648);
  EXPECT_EQ(MakeLensResidual(ideal, 0).ShiftPx(m.camera, {10.0, 20.0}), Eigen::Vector2d::Zero());
  cv::Mat1f signal(20, 30, 0.5f);
  ApplySpeckle(signal, ideal, 3.0, 7);
  EXPECT_EQ(cv::countNonZero(signal != 0.5f), 0);
  EXPECT_TRUE(RealismProfile("paper")->Any());
  EXPECT_FALSE(RealismProfile("real").has_value());
}

// A profile's pixels are the full-size module's: a quarter-size module gets a quarter of
// them (the same angles); the other members are physical and stay.
TEST(SpotErrors, AProfileScalesItsPixelsToTheModulesWidth) {
  const SpotErrors paper = *RealismProfile("paper");
  EXPECT_EQ(paper.reference_width_px, 2592);
  const SpotErrors quarter = AtCameraWidth(paper, 648);
  EXPECT_DOUBLE_EQ(quarter.placement_sigma_px, paper.placement_sigma_px / 4.0);
  EXPECT_DOUBLE_EQ(quarter.calibration_focal_px, paper.calibration_focal_px / 4.0);
  EXPECT_DOUBLE_EQ(quarter.calibration_centre_px, paper.calibration_centre_px / 4.0);
  EXPECT_EQ(quarter.calibration_baseline_mm, paper.calibration_baseline_mm);
  EXPECT_EQ(quarter.relief_mm, paper.relief_mm);
  EXPECT_EQ(quarter.reference_width_px, 0);
  EXPECT_EQ(AtCameraWidth(paper, 2592).placement_sigma_px, paper.placement_sigma_px);
  // Pixels of the module itself: unchanged at any width.
  SpotErrors own;
  own.placement_sigma_px = 0.3;
  EXPECT_EQ(AtCameraWidth(own, 648).placement_sigma_px, 0.3);
}

TEST(SpotErrors, ElementPlacementAndGainHaveTheSpreadAsked) {
  SpotErrors e;
  e.placement_sigma_px = 0.3;
  e.gain_sigma = 0.1;
  double sum2 = 0.0, gain_sum = 0.0, gain_sum2 = 0.0;
  const int n = 100;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      sum2 += ElementOffset(e, r, c).squaredNorm();
      const double g = ElementGain(e, r, c);
      gain_sum += g;
      gain_sum2 += g * g;
    }
  }
  const double count = n * n;
  // 10 000 elements: the estimates are within 2 % (3 sigma of a variance estimate: 4 %).
  EXPECT_NEAR(std::sqrt(sum2 / (2.0 * count)), 0.3, 0.3 * 0.04);
  EXPECT_NEAR(gain_sum / count, 1.0, 0.005);
  EXPECT_NEAR(std::sqrt(gain_sum2 / count - std::pow(gain_sum / count, 2)), 0.1, 0.1 * 0.04);
  // Fixed per element (a property of the projector), another for another projector.
  EXPECT_EQ(ElementOffset(e, 5, 6), ElementOffset(e, 5, 6));
  SpotErrors other = e;
  other.projector_seed = 2;
  EXPECT_NE(ElementOffset(other, 5, 6), ElementOffset(e, 5, 6));
}

TEST(SpotErrors, WallReliefHasTheRmsAndScaleAsked) {
  SpotErrors e;
  e.relief_mm = 0.05;
  e.relief_scale_mm = 0.5;
  double sum = 0.0, sum2 = 0.0, near = 0.0, far = 0.0;
  const int n = 200;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector2d p(0.37 * i, 0.41 * j);
      const double h = WallRelief(e, Material::kConcrete, 9, p);
      sum += h;
      sum2 += h * h;
      near += h * WallRelief(e, Material::kConcrete, 9,
                             p + Eigen::Vector2d(0.05, 0.0));  // a tenth of the scale
      far += h * WallRelief(e, Material::kConcrete, 9,
                            p + Eigen::Vector2d(5.0, 0.0));  // ten times the scale
    }
  }
  const double count = n * n;
  EXPECT_NEAR(sum / count, 0.0, 0.002);
  EXPECT_NEAR(std::sqrt(sum2 / count), 0.05, 0.05 * 0.1);  // bilinear: RMS varies in a cell
  EXPECT_GT(near / sum2, 0.8);                             // smooth below the scale
  EXPECT_LT(std::abs(far / sum2), 0.05);                   // independent beyond it
}

TEST(SpotErrors, LensResidualVanishesAtThePrincipalPointAndGrowsOutward) {
  SpotErrors e;
  e.lens_residual = 1e-4;
  const ModuleDescription m = testing::SmallDefaultModule(648);
  const CameraIntrinsics& k = m.camera;
  const LensResidual camera = MakeLensResidual(e, 0), projector = MakeLensResidual(e, 1);
  EXPECT_LT(camera.ShiftPx(k, {k.cx, k.cy}).norm(), 1e-12);
  const double mid = camera.ShiftPx(k, {k.cx + 0.25 * k.fx, k.cy}).norm();
  const double edge = camera.ShiftPx(k, {k.cx + 0.5 * k.fx, k.cy}).norm();
  // Quadratic in the distance from the principal point: twice as far, four times the shift;
  // at r = 0.5 the terms sum to at most 1.5e-4 · 0.25 · 2 of the focal length.
  EXPECT_NEAR(edge, 4.0 * mid, 1e-9);
  EXPECT_GT(edge, 0.0);
  EXPECT_LT(edge, 1e-4 * 0.25 * 4.0 * k.fx);
  // Camera and projector lenses err in their own directions.
  EXPECT_NE(camera.ShiftPx(k, {0.0, 0.0}), projector.ShiftPx(k, {0.0, 0.0}));
}

TEST(SpotErrors, SpeckleKeepsTheMeanAndHasTheContrastAsked) {
  SpotErrors e;
  e.speckle_contrast = 0.5;
  cv::Mat1f signal(400, 400, 0.4f);
  // A grain of 20 px (Airy diameter): the field's sigma is 1.4 px, well resolved.
  ApplySpeckle(signal, e, 20.0, 3);
  cv::Scalar mean, deviation;
  cv::meanStdDev(signal, mean, deviation);
  EXPECT_NEAR(mean[0], 0.4, 0.4 * 0.01);
  // Fully developed speckle has contrast 1; half of it mixed with uniform light: 0.5.
  EXPECT_NEAR(deviation[0] / mean[0], 0.5, 0.05);
  // A grain whose correlation (Airy diameter / 5.75) is below half a pixel averages out in
  // the pixel: the contrast falls in proportion, here to 0.5 · 0.348 / 0.5.
  cv::Mat1f fine(400, 400, 0.4f);
  ApplySpeckle(fine, e, 2.0, 3);
  cv::meanStdDev(fine, mean, deviation);
  EXPECT_NEAR(deviation[0] / mean[0], 0.5 * (2.0 / (2.44 * 2.355)) / 0.5, 0.04);
}

TEST(SpotErrors, CalibrationErrorMovesTheModuleByTheSigmasAsked) {
  const ModuleDescription m = testing::SmallDefaultModule(648);
  SpotErrors e;
  EXPECT_EQ(ActualModule(m, e).camera.fx, m.camera.fx);
  e.calibration_focal_px = 0.5;
  e.calibration_centre_px = 0.3;
  e.calibration_baseline_mm = 0.02;
  e.calibration_rotation_deg = 0.01;
  double focal2 = 0.0, centre2 = 0.0, baseline2 = 0.0, angle2 = 0.0;
  const int modules = 1000;
  const Rigid3d calibrated_from_projector = m.projector_from_camera.Inverse();
  for (int seed = 1; seed <= modules; ++seed) {
    e.projector_seed = seed;
    const ModuleDescription a = ActualModule(m, e);
    for (const auto& [k, k0] :
         {std::pair{a.camera, m.camera}, std::pair{a.projector, m.projector}}) {
      focal2 += std::pow(k.fx - k0.fx, 2) + std::pow(k.fy - k0.fy, 2);
      centre2 += std::pow(k.cx - k0.cx, 2) + std::pow(k.cy - k0.cy, 2);
    }
    const Rigid3d actual_from_projector = a.projector_from_camera.Inverse();
    baseline2 +=
        (actual_from_projector.translation - calibrated_from_projector.translation).squaredNorm();
    angle2 += std::pow(Eigen::AngleAxisd(calibrated_from_projector.rotation.conjugate() *
                                         actual_from_projector.rotation)
                           .angle(),
                       2);
  }
  // 4000 draws per intrinsic (2.2 % on the standard deviation at 3 sigma), 3000 per axis of
  // the projector's centre and rotation.
  EXPECT_NEAR(std::sqrt(focal2 / (4.0 * modules)), 0.5, 0.5 * 0.035);
  EXPECT_NEAR(std::sqrt(centre2 / (4.0 * modules)), 0.3, 0.3 * 0.035);
  EXPECT_NEAR(std::sqrt(baseline2 / (3.0 * modules)), 0.02, 0.02 * 0.04);
  EXPECT_NEAR(RadToDeg(std::sqrt(angle2 / (3.0 * modules))), 0.01, 0.01 * 0.04);
  // The module's other parts stay: lens terms, sizes, the pattern layout.
  const ModuleDescription a = ActualModule(m, e);
  EXPECT_EQ(a.camera.k, m.camera.k);
  EXPECT_EQ(a.projector.width, m.projector.width);
  EXPECT_EQ(a.pattern.pitch_px, m.pattern.pitch_px);
}

// The wall's errors are the material's: plastic pipe is smooth where a mineral wall has its
// cement skin and grains, and scatters light further into itself. One relief height field,
// scaled per material.
TEST(SpotErrors, WallErrorsAreTheMaterialsOwn) {
  SpotErrors e;
  e.subsurface_mm = 0.03;
  e.subsurface_plastic_mm = 0.2;
  e.relief_mm = 0.05;
  e.relief_plastic_mm = 0.005;
  for (const Material m : {Material::kConcrete, Material::kVitrifiedClay, Material::kSediment,
                           Material::kPlastic, Material::kPolyethylene}) {
    const bool plastic = m == Material::kPlastic || m == Material::kPolyethylene;
    EXPECT_EQ(SubsurfaceMm(e, m), plastic ? 0.2 : 0.03);
    EXPECT_EQ(ReliefMm(e, m), plastic ? 0.005 : 0.05);
  }
  const Eigen::Vector2d p(12.3, 4.5);
  EXPECT_NEAR(WallRelief(e, Material::kPlastic, 3, p),
              0.1 * WallRelief(e, Material::kConcrete, 3, p), 1e-15);
  EXPECT_TRUE(e.Any());
  EXPECT_FALSE(ModuleOwnErrors(e).Any());  // the wall's, not the module's
  e.relief_plastic_mm = 1.5;
  EXPECT_THROW(e.Check(), std::invalid_argument);
  const SpotErrors paper = *RealismProfile("paper");
  EXPECT_LT(paper.relief_plastic_mm, 0.2 * paper.relief_mm);
}

TEST(SpotErrors, OutOfRangeValuesAreRefused) {
  SpotErrors e;
  e.placement_sigma_px = 3.0;
  EXPECT_THROW(e.Check(), std::invalid_argument);
  e = SpotErrors{};
  e.speckle_contrast = 1.5;
  EXPECT_THROW(e.Check(), std::invalid_argument);
  e = SpotErrors{};
  e.relief_mm = -0.1;
  EXPECT_THROW(e.Check(), std::invalid_argument);
  e = SpotErrors{};
  e.subsurface_plastic_mm = 3.0;
  EXPECT_THROW(e.Check(), std::invalid_argument);
  e = SpotErrors{};
  e.calibration_rotation_deg = 2.0;
  EXPECT_THROW(e.Check(), std::invalid_argument);
  EXPECT_NO_THROW(RealismProfile("paper")->Check());
}

}  // namespace
}  // namespace sewer3d
