#include "sewer3d/run/rig.hpp"

#include <cmath>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

void Rig::Check() const {
  SEWER3D_CHECK(!modules.empty(), "rig without modules");
  SEWER3D_CHECK(carrier_diameter_mm > 0.0 && carrier_length_mm > 0.0, "carrier size");
  for (const RigModule& m : modules) {
    m.module.Check();
    for (const Eigen::Vector3d& c :
         {m.carrier_from_camera.translation, ProjectorCentreInCarrier(m)}) {
      SEWER3D_CHECK(std::abs(c.z()) <= 0.5 * carrier_length_mm + 1e-6 &&
                        std::hypot(c.x(), c.y()) <= 0.5 * carrier_diameter_mm + 1e-6,
                    "module " << m.name << ": camera or projector outside the carrier");
    }
  }
}

Eigen::Vector3d ProjectorCentreInCarrier(const RigModule& m) {
  return m.carrier_from_camera * m.module.projector_from_camera.Inverse().translation;
}

}  // namespace sewer3d
