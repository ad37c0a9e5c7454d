#pragma once
/// \file
/// The inclinometer of a simulated run (sim/inclinometer.hpp): inclinometer.csv as the robot
/// reports it and truth/inclinometer.csv with every reading's true direction and the carrier's
/// acceleration. Written by SimulateRun with the rest of the run, or added to a run simulated
/// before the simulator had it (`sewer3d simulate inclinometer`), from its truth/scenario.json.

#include <filesystem>

#include "sewer3d/sim/scenario.hpp"
#include "sewer3d/sim/trajectory.hpp"

namespace sewer3d {

/// Writes `run`/inclinometer.csv and `run`/truth/inclinometer.csv (nothing where the scenario's
/// inclinometer is disabled); returns the readings written.
int WriteSimulatedInclinometer(const std::filesystem::path& run, const Scenario& scenario,
                               const Trajectory& trajectory);

/// The same for a simulated run on disk: the scenario from `run`/truth/scenario.json (FileError
/// naming it when it is missing or invalid), the trajectory rebuilt from it.
int AddSimulatedInclinometer(const std::filesystem::path& run);

}  // namespace sewer3d
