#pragma once
/// \file
/// The six-module carrier as designed (docs/simulator.md, "Rig"): modules rotated by 360°/n
/// around the carrier axis, camera and projector centres on the axis, modules staggered along
/// it (the Rig type itself is run/rig.hpp). Each camera looks radially outward, its y axis
/// along the carrier axis (the module's baseline), its x axis toward increasing clock.

#include <string>
#include <vector>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/run/rig.hpp"

namespace sewer3d {

struct RigOptions {
  int modules = 6;
  double first_clock_h = 12.0;  ///< module 0's direction; the others follow clockwise
  double stagger_mm = 90.0;     ///< axial spacing of the modules' centres
  double carrier_diameter_mm = 150.0;
  double carrier_length_mm = 600.0;

  void Check() const;
};

/// Places copies of `module` on the carrier; throws std::invalid_argument when they do not
/// fit in the carrier's length.
Rig MakeRig(const ModuleDescription& module, const RigOptions& options);

/// The part of a straight, round pipe wall one module covers, seen with the carrier at a
/// given offset from the pipe axis.
struct WallCoverage {
  bool any = false;
  double clock_from_deg = 0.0,
         clock_to_deg = 0.0;  ///< pipe clock angles, unwrapped around the module's
  double station_from_mm = 0.0, station_to_mm = 0.0;  ///< relative to the carrier centre
};

/// Casts camera rays every `step_px` pixels; with `lit`, counts only wall points the
/// projector also reaches (where depth can be measured).
WallCoverage ModuleCoverage(const Rig& rig, int module, double pipe_diameter_mm,
                            const Eigen::Vector2d& carrier_offset_mm, bool lit, int step_px = 8);

struct NeighbourOverlap {
  int module = 0, next = 0;
  double overlap_deg = 0.0;  ///< clock overlap of the two modules' coverage (negative: gap)
  double overlap_mm = 0.0;   ///< the same as arc length on the nominal wall
};

/// Overlap of each module with the next one around the carrier (n entries).
std::vector<NeighbourOverlap> NeighbourOverlaps(const Rig& rig, double pipe_diameter_mm,
                                                const Eigen::Vector2d& carrier_offset_mm, bool lit,
                                                int step_px = 8);

}  // namespace sewer3d
