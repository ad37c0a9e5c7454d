#pragma once
/// \file
/// Writes a virtual capture run (docs/formats.md): plans the acquisitions, renders every image
/// in parallel, writes the images as they finish, the rig, index, odometry and ground truth.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/pattern/binary_array.hpp"
#include "sewer3d/sim/rig.hpp"
#include "sewer3d/sim/scenario.hpp"

namespace sewer3d {

struct SimulatedRun {
  CapturePlan plan;
  int images = 0;
  double duration_s = 0.0;    ///< of the run (robot time)
  double wall_seconds = 0.0;  ///< to simulate it
  std::uintmax_t bytes = 0;   ///< on disk
  int images_kept = 0;        ///< of an interrupted simulation of the same run, not rendered again
  std::vector<NeighbourOverlap> overlap;  ///< 3-D coverage at the nominal diameter, centred
};

/// done / total images; called from the rendering threads, one call at a time.
using RunProgress = std::function<void(int done, int total)>;

/// What a run will take before it starts: images, bytes on disk (an estimate from measured
/// PNG and TIFF sizes), odometry rows, robot time.
struct RunSizeEstimate {
  int images = 0;
  std::uintmax_t bytes = 0;
  std::uint64_t odometry_rows = 0;
  double duration_s = 0.0;
};

/// Plans the run (as SimulateRun will) and estimates its size. InvalidValue in the scenario
/// file's terms when the scenario is invalid.
/// run.json's `created_by` of a simulated run.
inline constexpr const char* kSimulatedRunCreator = "sewer3d simulate run";
/// Whether `folder` holds a run the simulator made (run.json's created_by, a truth/ folder):
/// only such a run may be replaced by a new simulation.
bool IsSimulatedRun(const std::filesystem::path& folder);

RunSizeEstimate EstimateRunSize(const Scenario& scenario, const ModuleDescription& module);

/// Refuses (InvalidValue naming the scenario's size, the estimate and the limit) a run of more
/// than kMaxPlannedImages images or kMaxOdometryRows odometry rows, or more bytes than the file
/// system holding `out` has free. Call before SimulateRun unless the user overrides it.
void CheckRunFits(const RunSizeEstimate& size, const std::filesystem::path& out);
inline constexpr int kMaxPlannedImages = 200'000;
inline constexpr std::uint64_t kMaxOdometryRows = 20'000'000;

/// Every module of the rig uses `module` and `pattern` (its matrix is written as pattern.png).
/// A folder holding an interrupted simulation of the same run (run.json not complete; the same
/// scenario, rig and pattern) keeps the images it finished — every file of a shot written —
/// and renders the rest, unless `restart`: images are rendered independently and
/// deterministically, so the resumed run is the uninterrupted one. A folder holding any other
/// simulated run has its images and truth removed first (no stale image survives); a non-empty
/// folder that is not a simulated run is refused (FileError).
SimulatedRun SimulateRun(const Scenario& scenario, const ModuleDescription& module,
                         const BinaryArray& pattern, const std::filesystem::path& out,
                         const RunProgress& progress, bool restart = false);

}  // namespace sewer3d
