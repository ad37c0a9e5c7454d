#include "sewer3d/run/rig.hpp"

#include <cmath>
#include <set>
#include <string>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

void Rig::Check() const {
  // Field names as in rig.json.
  SEWER3D_VALIDATE(!modules.empty(), "modules", "must list at least one module");
  ValidatePositive("carrier.diameter_mm", carrier_diameter_mm);
  ValidatePositive("carrier.length_mm", carrier_length_mm);
  std::set<std::string> names;
  for (size_t i = 0; i < modules.size(); ++i) {
    const RigModule& m = modules[i];
    const std::string field = "modules[" + std::to_string(i) + "].";
    SEWER3D_VALIDATE(!m.name.empty(), field + "name", "must not be empty");
    SEWER3D_VALIDATE(names.insert(m.name).second, field + "name",
                     "module name '" << m.name << "' is used twice");
    ValidateClockHours(field + "clock_h", m.clock_h);
    // clock_h names where the camera looks (12 h up: −y of the carrier, 3 h: +x); the pose is
    // what is used, so the two must agree (a hand edit of one alone is a silent error).
    const Eigen::Vector3d view = m.carrier_from_camera.RotationMatrix().col(2);
    if (std::hypot(view.x(), view.y()) > 0.3) {
      double looks_h = std::atan2(view.x(), -view.y()) * 6.0 / M_PI;
      if (looks_h <= 0.0) looks_h += 12.0;
      const double off_h = std::remainder(looks_h - m.clock_h, 12.0);
      SEWER3D_VALIDATE(std::abs(off_h) <= 0.75, field + "clock_h",
                       m.clock_h << " h, but carrier_from_camera has the camera look toward "
                                 << looks_h << " h (they must agree within 0.75 h)");
    }
    CheckWithin(field + "module.", [&] { m.module.Check(); });
    for (const Eigen::Vector3d& c :
         {m.carrier_from_camera.translation, ProjectorCentreInCarrier(m)}) {
      SEWER3D_VALIDATE(
          std::abs(c.z()) <= 0.5 * carrier_length_mm + 1e-6 &&
              std::hypot(c.x(), c.y()) <= 0.5 * carrier_diameter_mm + 1e-6,
          field + "carrier_from_camera",
          "puts the camera or projector of module " << m.name << " outside the carrier");
    }
    // Two cameras cannot share one place: a rig written with every camera at the carrier's
    // centre would override the measurements with impossible rig edges.
    constexpr double kMinCameraSpacingMm = 5.0;
    for (size_t k = 0; k < i; ++k) {
      const double d =
          (m.carrier_from_camera.translation - modules[k].carrier_from_camera.translation).norm();
      SEWER3D_VALIDATE(d >= kMinCameraSpacingMm, field + "carrier_from_camera",
                       "puts the camera of module " << m.name << " " << d << " mm from that of "
                                                    << modules[k].name << " (modules[" << k
                                                    << "]): cameras are at least "
                                                    << kMinCameraSpacingMm << " mm apart");
    }
  }
}

Eigen::Vector3d ProjectorCentreInCarrier(const RigModule& m) {
  return m.carrier_from_camera * m.module.projector_from_camera.Inverse().translation;
}

}  // namespace sewer3d
