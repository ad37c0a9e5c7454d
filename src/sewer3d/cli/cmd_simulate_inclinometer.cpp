// `sewer3d simulate inclinometer --run RUN`: writes the inclinometer a simulated run's robot
// had (inclinometer.csv, truth/inclinometer.csv) from its truth/scenario.json, for runs
// simulated before the simulator wrote it; `simulate run` writes it with the rest.

#include <fmt/format.h>

#include <filesystem>

#include "sewer3d/cli/simulate_commands.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/simio/simulate_inclinometer.hpp"
#include "sewer3d/simio/simulate_run.hpp"

namespace sewer3d::cli {

void AddInclinometerCommand(CLI::App& sim, InclinometerArgs& args) {
  args.app = sim.add_subcommand(
      "inclinometer",
      "Add the robot's inclinometer (inclinometer.csv) to a run simulated without it, from its "
      "truth/scenario.json");
  args.app->add_option("--run", args.run, "Simulated capture run folder")->required();
}

int RunInclinometer(const InclinometerArgs& args) {
  const std::filesystem::path run = args.run;
  if (!IsSimulatedRun(run))
    throw FileError(run,
                    "is not a simulated run (no run.json made by the simulator, or no truth/)");
  const int readings = AddSimulatedInclinometer(run);
  if (readings == 0) {
    fmt::print("{}: the scenario's inclinometer is disabled; nothing written\n", args.run);
    return 0;
  }
  fmt::print("wrote {}/inclinometer.csv ({} readings) and truth/inclinometer.csv\n", args.run,
             readings);
  return 0;
}

}  // namespace sewer3d::cli
