#include "sewer3d/simio/simulate_inclinometer.hpp"

#include <fmt/format.h>

#include <string>
#include <vector>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/inclinometer_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/sim/inclinometer.hpp"
#include "sewer3d/sim/pipe_world.hpp"
#include "sewer3d/simio/scenario_io.hpp"

namespace sewer3d {
namespace {

void WriteTruth(const std::filesystem::path& path, const std::vector<InclinometerSample>& samples) {
  std::string text =
      "time_s,true_down_x,true_down_y,true_down_z,accel_x_mm_s2,accel_y_mm_s2,accel_z_mm_s2,"
      "measured_down_x,measured_down_y,measured_down_z\n";
  for (const InclinometerSample& s : samples) {
    const Eigen::Vector3d &t = s.true_down, &a = s.acceleration_mm_s2, &m = s.measured_down;
    text += fmt::format("{:.6f},{:.9f},{:.9f},{:.9f},{:.3f},{:.3f},{:.3f},{:.9f},{:.9f},{:.9f}\n",
                        s.time_s, t.x(), t.y(), t.z(), a.x(), a.y(), a.z(), m.x(), m.y(), m.z());
  }
  WriteTextFile(path, text);
}

}  // namespace

int WriteSimulatedInclinometer(const std::filesystem::path& run, const Scenario& scenario,
                               const Trajectory& trajectory) {
  const std::vector<InclinometerSample> samples =
      SimulateInclinometer(trajectory, scenario.inclinometer, scenario.seed);
  if (samples.empty()) return 0;
  std::vector<InclinometerReading> readings;
  for (const InclinometerSample& s : samples) readings.push_back({s.time_s, s.measured_down, 0});
  WriteInclinometer(run / "inclinometer.csv", readings);
  WriteTruth(run / "truth" / "inclinometer.csv", samples);
  return static_cast<int>(readings.size());
}

int AddSimulatedInclinometer(const std::filesystem::path& run) {
  const Scenario scenario = ReadScenario(run / "truth" / "scenario.json");
  const PipeGeometry pipe(scenario.world);
  const Trajectory trajectory(pipe, scenario.motion, scenario.seed);
  return WriteSimulatedInclinometer(run, scenario, trajectory);
}

}  // namespace sewer3d
