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
  double duration_s = 0.0;                ///< of the run (robot time)
  double wall_seconds = 0.0;              ///< to simulate it
  std::uintmax_t bytes = 0;               ///< on disk
  std::vector<NeighbourOverlap> overlap;  ///< 3-D coverage at the nominal diameter, centred
};

/// done / total images; called from the rendering threads, one call at a time.
using RunProgress = std::function<void(int done, int total)>;

/// Every module of the rig uses `module` and `pattern` (its matrix is written as pattern.png).
SimulatedRun SimulateRun(const Scenario& scenario, const ModuleDescription& module,
                         const BinaryArray& pattern, const std::filesystem::path& out,
                         const RunProgress& progress);

}  // namespace sewer3d
