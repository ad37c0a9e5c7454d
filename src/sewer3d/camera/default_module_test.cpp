#include "sewer3d/camera/default_module.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sewer3d/core/units.hpp"

namespace sewer3d {
namespace {

TEST(DefaultModule, FieldCentresMeetAtMidRangeWithTheStereoAngle) {
  const DefaultModuleOptions options;
  const ModuleDescription m = MakeDefaultModule(options);
  ASSERT_NO_THROW(m.Check());
  const CameraModel camera(m.camera), projector(m.projector);
  const Eigen::Vector2d centre((m.camera.width - 1) / 2.0, (m.camera.height - 1) / 2.0);
  const Eigen::Vector3d ray = *camera.Ray(centre);
  const Eigen::Vector3d point = ray * (150.0 / ray.z());
  const Eigen::Vector2d seen = *projector.Project(m.projector_from_camera * point);
  EXPECT_NEAR(seen.x(), (m.projector.width - 1) / 2.0, 1e-6);
  EXPECT_NEAR(seen.y(), (m.projector.height - 1) / 2.0, 1e-6);
  // Angle between the two rays at the point: the paper's stereo angle.
  const Eigen::Vector3d projector_centre = m.projector_from_camera.Inverse().translation;
  const double angle = std::acos(ray.dot((point - projector_centre).normalized()));
  EXPECT_NEAR(RadToDeg(angle), 29.0, 1e-9);
  EXPECT_NEAR(projector_centre.y(), 2.0 * 150.0 * std::tan(DegToRad(14.5)), 1e-9);  // 77.58 mm
  EXPECT_NEAR(projector_centre.x(), 0.0, 1e-12);
  EXPECT_NEAR(projector_centre.z(), 0.0, 1e-12);
}

TEST(DefaultModule, HorizontalFieldIs76DegreesAndLensVerticalAbout61) {
  const ModuleDescription m = MakeDefaultModule({});
  const CameraModel camera(m.camera);
  ASSERT_TRUE(camera.WholeImageInvertible());
  const auto left = camera.Unproject({-0.5, m.camera.cy});
  const auto right = camera.Unproject({m.camera.width - 0.5, m.camera.cy});
  EXPECT_NEAR(RadToDeg(std::atan(right->x()) - std::atan(left->x())), 76.0, 1e-9);
  const DefaultModuleGeometry g = DescribeDefaultModule({});
  // The paper's 76° x 61° lens; barrel distortion trims the vertical field a little.
  EXPECT_NEAR(g.lens_vertical_fov_deg, 61.0, 1.5);
  // Sensor shift: the field is tilted by 14.5° toward the projector (+y).
  const Eigen::Vector3d centre = *camera.Ray({m.camera.cx, (m.camera.height - 1) / 2.0});
  EXPECT_NEAR(RadToDeg(std::atan2(centre.y(), centre.z())), 14.5, 1e-9);
  EXPECT_LT(g.field_top_deg, 0.0);
  EXPECT_GT(g.field_bottom_deg, 14.5);
  EXPECT_TRUE(CameraModel(m.projector).WholeImageInvertible());
}

TEST(DefaultModule, EpipolarLinesAreProjectorRowsWithoutDistortion) {
  // With the projector rolled by 90°, a camera ray's points share the projector's y: epipolar
  // lines are exactly rows. Lens distortion bends them (by up to ~8 rows at the image corners),
  // which calibrated geometry accounts for.
  DefaultModuleOptions options;
  options.k = {0.0, 0.0, 0.0};
  const DisparityRange ideal = ComputeDisparityRange(
      MakeDefaultModule(options), kWorkingDistanceMinMm, kWorkingDistanceMaxMm, 8);
  EXPECT_LT(ideal.max_dv_px, 1e-9);
  const double f = MakeDefaultModule(options).camera.fx;
  const double b = 2.0 * 150.0 * std::tan(DegToRad(14.5));
  EXPECT_NEAR(ideal.max_du_px, f * b * (1.0 / 75.0 - 1.0 / 225.0), 1e-6);
}

TEST(DefaultModule, ReducedCameraKeepsTheGeometry) {
  DefaultModuleOptions options;
  options.camera_width = 648;
  options.camera_height = 486;
  const ModuleDescription small = MakeDefaultModule(options);
  const ModuleDescription full = MakeDefaultModule({});
  EXPECT_NEAR(small.camera.fx * 4.0, full.camera.fx, 1e-9);
  EXPECT_EQ(small.projector.width, 486);
  EXPECT_EQ(small.projector.height, 648);
  EXPECT_NEAR(small.projector_from_camera.translation.norm(),
              full.projector_from_camera.translation.norm(), 1e-12);
  EXPECT_THROW(MakeDefaultModule({.camera_width = 4}), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
