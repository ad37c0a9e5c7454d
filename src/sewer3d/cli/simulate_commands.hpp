#pragma once
/// \file
/// Pieces of `sewer3d simulate` kept in their own files.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/sim/scene.hpp"

namespace sewer3d::cli {

/// `sewer3d simulate frame`'s arguments.
struct FrameArgs {
  std::string module, scene = "plane", out, material = "concrete";
  double distance = 140.0, tilt = 0.0, diameter = 300.0;
  std::vector<double> decentre{0.0, 0.0};
  std::vector<double> axis{0.0, 1.0, 0.0};
  bool ideal = false;
  std::string realism = "ideal";  ///< the projector's and wall's error sources (spot_errors.hpp)
  RenderOptions render;
};

/// The scene `simulate frame` renders: a built-in one (plane, cylinder, pipe-wall) from the
/// geometry flags, or a scene file with its render options (the render flags given on the
/// command line over them, into `options`). InvalidValue naming the flag for a flag that does
/// not apply or a geometry that is not valid.
Scene FrameScene(const FrameArgs& args, const CLI::App& frame, RenderOptions& options);

struct CalibrationArgs {
  CLI::App* app = nullptr;
  std::string module, out, board = "9x6";
  int poses = 20;
  std::uint64_t seed = 1;
  double square_mm = 10.0;
  int supersampling = 3;
  /// The board images' square edges alias at S < 4 (corner errors ~0.2 px at S = 2, 0.1 px
  /// at S = 4, measured against the true corners).
  int texture_supersampling = 4;
  std::string realism = "ideal";  ///< RealismProfile: the projector's and lens's errors
  bool quiet = false;
};

void AddCalibrationCommand(CLI::App& sim, CalibrationArgs& args);
int RunCalibration(const CalibrationArgs& args);

/// `sewer3d simulate inclinometer --run RUN`: adds the inclinometer to a simulated run.
struct InclinometerArgs {
  CLI::App* app = nullptr;
  std::string run;
};

void AddInclinometerCommand(CLI::App& sim, InclinometerArgs& args);
int RunInclinometer(const InclinometerArgs& args);

/// `sewer3d simulate run`'s arguments (0 / empty: the scenario's).
struct RunArgs {
  std::string scenario, preset, out, module;
  std::uint64_t seed = 0;
  int supersampling = 0;
  std::string realism;  ///< RealismProfile over the scenario's error sources
  bool quiet = false;
  bool allow_large = false;  ///< skip CheckRunFits
  bool restart = false;      ///< render every image, keeping nothing of an interrupted simulation
};

/// Registers `simulate run` under `simulate`.
CLI::App* AddRunCommand(CLI::App& sim, RunArgs& args);
/// Simulates the run (progress bar unless quiet), prints what it wrote; returns the exit code.
int RunRun(const RunArgs& args);

}  // namespace sewer3d::cli
