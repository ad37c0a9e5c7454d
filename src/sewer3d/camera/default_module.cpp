#include "sewer3d/camera/default_module.hpp"

#include <cmath>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"

namespace sewer3d {
namespace {

// Radial map of the lens applied to a radius.
double DistortRadius(const std::array<double, 3>& k, double r) {
  const double s = r * r;
  return r * (1.0 + s * (k[0] + s * (k[1] + s * k[2])));
}

struct Derived {
  double focal_px, tilt_rad, baseline_mm, shift_px;
};

Derived Derive(const DefaultModuleOptions& o) {
  Derived d;
  // The image edge (half a pixel beyond the outer pixel centres) sees half the field.
  const double x_edge = std::tan(DegToRad(0.5 * o.horizontal_fov_deg));
  d.focal_px = 0.5 * o.camera_width / DistortRadius(o.k, x_edge);
  // Field centres, tilted by half the stereo angle each, cross at the meeting distance.
  d.tilt_rad = DegToRad(0.5 * o.stereo_angle_deg);
  d.baseline_mm = 2.0 * o.meeting_distance_mm * std::tan(d.tilt_rad);
  // Sensor shift: the image centre pixel looks along the tilted field centre.
  d.shift_px = d.focal_px * DistortRadius(o.k, std::tan(d.tilt_rad));
  return d;
}

}  // namespace

void DefaultModuleOptions::Check() const {
  SEWER3D_VALIDATE(camera_width >= 16 && camera_height >= 16, "camera_size",
                   "must be at least 16x16, got " << camera_width << "x" << camera_height);
  SEWER3D_VALIDATE(horizontal_fov_deg > 1.0 && horizontal_fov_deg < 160.0, "horizontal_fov_deg",
                   "must be > 1 and < 160, got " << horizontal_fov_deg);
  SEWER3D_VALIDATE(stereo_angle_deg > 0.0 && stereo_angle_deg < 90.0, "stereo_angle_deg",
                   "must be > 0 and < 90, got " << stereo_angle_deg);
  ValidatePositive("meeting_distance_mm", meeting_distance_mm);
  ValidatePositive("pitch_px", pitch_px);
  SEWER3D_VALIDATE(
      spot_diameter_px > 0.0 && spot_diameter_px <= pitch_px, "spot_diameter_px",
      "must be > 0 and at most pitch_px (" << pitch_px << "), got " << spot_diameter_px);
}

DefaultModuleGeometry DescribeDefaultModule(const DefaultModuleOptions& o) {
  o.Check();
  const Derived d = Derive(o);
  DefaultModuleGeometry g;
  g.focal_px = d.focal_px;
  g.field_tilt_deg = RadToDeg(d.tilt_rad);
  g.baseline_mm = d.baseline_mm;
  const ModuleDescription m = MakeDefaultModule(o);
  const CameraModel camera(m.camera);
  const auto half = camera.Undistort({0.0, 0.5 * o.camera_height / d.focal_px});
  const auto top = camera.Unproject({m.camera.cx, -0.5});
  const auto bottom = camera.Unproject({m.camera.cx, m.camera.height - 0.5});
  if (half) g.lens_vertical_fov_deg = RadToDeg(2.0 * std::atan(half->y()));
  if (top) g.field_top_deg = RadToDeg(std::atan(top->y()));
  if (bottom) g.field_bottom_deg = RadToDeg(std::atan(bottom->y()));
  return g;
}

ModuleDescription MakeDefaultModule(const DefaultModuleOptions& o) {
  o.Check();
  const Derived d = Derive(o);
  const double f = d.focal_px, baseline = d.baseline_mm, shift_px = d.shift_px;

  ModuleDescription m;
  m.camera.width = o.camera_width;
  m.camera.height = o.camera_height;
  m.camera.fx = m.camera.fy = f;
  m.camera.cx = 0.5 * (o.camera_width - 1);
  // The camera's field centre looks toward +y (the projector): y_d > 0 at the image centre.
  m.camera.cy = 0.5 * (o.camera_height - 1) - shift_px;
  m.camera.k = o.k;

  // Projector: same lens and sensor format, rolled by 90°: its x axis is camera +y.
  m.projector = m.camera;
  m.projector.width = o.camera_height;
  m.projector.height = o.camera_width;
  // The camera lies at projector x = -b, so the projector's field centre looks toward -x.
  m.projector.cx = 0.5 * (m.projector.width - 1) + shift_px;
  m.projector.cy = 0.5 * (m.projector.height - 1);

  Eigen::Matrix3d r;
  r << 0, 1, 0,  //
      -1, 0, 0,  //
      0, 0, 1;
  // Projector centre at camera (0, b, 0): t = -R c.
  m.projector_from_camera = Rigid3d(r, -r * Eigen::Vector3d(0.0, baseline, 0.0));

  m.pattern.matrix_path = o.matrix_path;
  m.pattern.pitch_px = o.pitch_px;
  m.pattern.spot_diameter_px = o.spot_diameter_px;
  return m;
}

}  // namespace sewer3d
