#pragma once
/// \file
/// Which acquisitions to register with which (paper §4.1): candidates by coarse position
/// (their footprints on the pipe overlap along it), then the overlap estimated by projecting a
/// mock-up cylinder, without building any cloud: a coarse grid of a's pixels is cast onto a
/// cylinder of the nominal diameter whose axis runs along model z through the estimated
/// carrier offset, and the fraction of those wall points that b's camera sees (in front of it,
/// inside its image) is a's overlap with b. Pairs are kept above a threshold, along the pipe
/// (same module, consecutive counters) and around it (neighbouring modules).

#include <Eigen/Core>
#include <vector>

#include "sewer3d/register/initial_poses.hpp"
#include "sewer3d/run/rig.hpp"

namespace sewer3d {

enum class PairKind { kAlong, kAround };

/// "along" or "around".
const char* PairKindName(PairKind kind);

struct NeighbourOptions {
  double nominal_diameter_mm = 300.0;
  /// Where the mock-up cylinder's axis (parallel to model z) crosses the model x-y plane;
  /// from EstimateCarrierOffset: the carrier's pose at the first image applied to
  /// axis_in_carrier_mm, i.e. the same vector when the carrier starts unrolled.
  Eigen::Vector2d axis_in_model_mm = Eigen::Vector2d::Zero();
  int grid_step_px = 16;         ///< pixel grid on a's image (at full size: 64 or more)
  double min_overlap = 0.1;      ///< keep pairs whose smaller overlap fraction reaches this
  int max_counter_gap = 1;       ///< along the pipe: counters this far apart at most
  bool along = true;             ///< consider same-module pairs
  bool around = true;            ///< consider pairs of neighbouring modules (cyclic order)
  double station_margin_mm = 0;  ///< widens the coarse footprint test

  void Check() const;
};

struct NeighbourPair {
  int a = 0, b = 0;  ///< indices into the nodes, a < b
  PairKind kind = PairKind::kAlong;
  double overlap_ab = 0.0;  ///< fraction of a's wall samples seen by b
  double overlap_ba = 0.0;  ///< fraction of b's wall samples seen by a
  double Overlap() const { return overlap_ab < overlap_ba ? overlap_ab : overlap_ba; }
};

struct NeighbourReport {
  int nodes = 0;
  int candidates = 0;          ///< pairs of an allowed kind whose footprints meet along z
  int kept = 0;                ///< overlap ≥ min_overlap
  int rejected_overlap = 0;    ///< candidates below the threshold
  int nodes_without_wall = 0;  ///< none of the node's samples hit the mock-up cylinder
};

struct NeighbourResult {
  std::vector<NeighbourPair> pairs;  ///< ordered by (a, b)
  NeighbourReport report;
};

/// Pairs of `nodes` (initial poses, model frame) worth registering; cameras from the rig's
/// modules. Throws std::invalid_argument for bad options or a node's module missing in the rig.
NeighbourResult FindNeighbours(const std::vector<AcquisitionNode>& nodes, const Rig& rig,
                               const NeighbourOptions& options);

}  // namespace sewer3d
