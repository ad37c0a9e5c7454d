#pragma once
/// \file
/// The carrier and its modules as a capture run describes them (docs/formats.md, rig.json):
/// each module's description (camera, projector, pattern) and where its camera sits on the
/// carrier. Carrier frame: z along the carrier axis (forward), y down and x right when the
/// robot is upright, origin at the carrier's centre. The simulator builds a rig from the
/// design (sim/rig.hpp); a real robot's comes from calibration.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/core/rigid3.hpp"

namespace sewer3d {

struct RigModule {
  std::string name;
  double clock_h = 12.0;  ///< nominal viewing direction on the carrier (EN 13508-2 clock)
  ModuleDescription module;
  Rigid3d carrier_from_camera;
};

struct Rig {
  double carrier_diameter_mm = 150.0;
  double carrier_length_mm = 600.0;
  std::vector<RigModule> modules;

  /// Throws std::invalid_argument when there is no module, a module is invalid or a camera or
  /// projector centre lies outside the carrier.
  void Check() const;
};

/// Centre of a module's projector in the carrier frame.
Eigen::Vector3d ProjectorCentreInCarrier(const RigModule& m);

}  // namespace sewer3d
