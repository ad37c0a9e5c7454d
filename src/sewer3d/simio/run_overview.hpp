#pragma once
/// \file
/// A picture of a simulated run for people: the unrolled true pipe wall with where each
/// module's pattern images fall on it.

#include <opencv2/core.hpp>

#include "sewer3d/sim/pipe_world.hpp"
#include "sewer3d/sim/rig.hpp"
#include "sewer3d/sim/trajectory.hpp"

namespace sewer3d {

/// Station runs left to right (mm_per_px), the clock top to bottom from 12 through 3, 6, 9
/// back to 12 (arc length on the first section's nominal wall). The wall is drawn in its
/// material's colour, tinted red where it is displaced inward and blue where outward (full
/// tint at `range_mm`); each pattern image's outline is drawn in its module's colour; grid
/// lines every 100 mm and every 3 h.
cv::Mat3b RunOverview(const PipeGeometry& pipe, const Rig& rig, const Trajectory& trajectory,
                      const CapturePlan& plan, double mm_per_px = 2.0, double range_mm = 10.0);

}  // namespace sewer3d
