#pragma once
/// \file
/// Everything that defines a virtual inspection run (docs/simulator.md, "Scenario files"):
/// the pipe world, the rig, the robot's motion, capture timing, odometry errors and render
/// settings; plus the built-in presets tiny, compact, demo and long.

#include <cstdint>
#include <string>
#include <vector>

#include "sewer3d/sim/inclinometer.hpp"
#include "sewer3d/sim/odometry.hpp"
#include "sewer3d/sim/pipe_world.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/sim/rig.hpp"
#include "sewer3d/sim/trajectory.hpp"

namespace sewer3d {

enum class TruthDepth { kAll, kPattern, kNone };

/// A run's render options unless its scenario says otherwise: the renderer's defaults with the
/// `paper` realism profile's error sources (a simulated run errs as real captures do;
/// "realism": "ideal" in a scenario's render options turns them off).
RenderOptions RunRenderDefaults();

struct Scenario {
  std::string name = "custom";
  std::uint64_t seed = 1;
  /// Module file for every module of the rig (relative to the scenario file); empty: the
  /// default module with camera_width (height and projector scaled alike).
  std::string module_file;
  int camera_width = 2592;
  RigOptions rig;
  PipeWorld world;
  MotionOptions motion;
  CaptureOptions capture;
  OdometryOptions odometry;
  InclinometerOptions inclinometer;
  RenderOptions render = RunRenderDefaults();
  TruthDepth truth_depth = TruthDepth::kPattern;  ///< which images get a truth depth map
  /// Each module's camera white balance is off by gains exp(σ n) on R and B (n standard normal
  /// from the seed and the module, G = 1): σ = this (docs/simulated_run.md).
  double white_balance_error = 0.04;
  bool truth_albedo = false;  ///< write truth/albedo/ for every texture image

  void Check() const;  ///< throws std::invalid_argument
};

/// The white-balance gains (R, G, B) of module `module`'s camera in `scenario`'s run.
Eigen::Vector3d CameraWhiteBalance(const Scenario& scenario, int module);

const std::vector<std::string>& PresetNames();
/// Every preset but tiny renders with the `paper` realism profile (RunRenderDefaults).
/// tiny: 648 × 486 images, DN300 concrete with a displaced joint, two acquisitions (tests;
/// realism ideal);
/// compact: 648 × 486 images, DN300, 0.56 m of travel: concrete, displaced joint, intruding
/// connection, then plastic (`sewer3d demo`); demo: full-size images, DN300, 1 m of travel:
/// concrete, displaced joint, intruding connection, spalled patch, crack, then plastic; long: 10 m
/// with every kind of feature. Texture images: full colour with truth albedo (tiny), Bayer RGGB
/// with truth albedo (compact, demo), Bayer RGGB without (long). Throws std::invalid_argument for
/// an unknown name.
Scenario PresetScenario(const std::string& name);

}  // namespace sewer3d
