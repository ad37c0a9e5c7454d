#pragma once
/// \file
/// The pairwise part of the registration stage: every neighbour pair registered once (feature
/// registration, else projection registration from the initial poses), its result cached in
/// WS/registration/pairs/ so that an interrupted stage resumes without redoing finished pairs.
/// Streaming: a worker holds the two acquisitions of one pair at a time.

#include <filesystem>
#include <functional>
#include <vector>

#include "sewer3d/io/registration_io.hpp"
#include "sewer3d/register/feature_registration.hpp"
#include "sewer3d/register/neighbours.hpp"
#include "sewer3d/register/prior_edges.hpp"
#include "sewer3d/register/projection_registration.hpp"
#include "sewer3d/run/rig.hpp"

namespace sewer3d {

struct PairRegistrationOptions {
  FeatureRegistrationOptions features;
  ProjectionRegistrationOptions projection;
  bool feature_registration = true;  ///< try feature registration first (ablation: off)
  bool projection_fallback = true;   ///< try projection registration where features fail
  /// A further covariance floor (information.hpp, WithCovarianceFloor) on pairs of two modules:
  /// each module's own calibration error biases their relative pose, and unlike in a pair of
  /// one module it does not cancel (docs/registration.md, "Pairs of two modules").
  double between_modules_floor_mm = 0.25;
  double between_modules_floor_deg = 0.07;
};

struct PairRegistrationOutcome {
  std::vector<PairRecord> records;  ///< one per pair, as the pairs
  int done = 0;                     ///< registered now
  int skipped = 0;                  ///< read from the cache (an earlier run)
  double seconds_now = 0.0;         ///< sum over the pairs registered now (one worker each)
};

/// Registers (or reads back) every pair. `rgbd_folder` = WS/rgbd, `pairs_folder` =
/// WS/registration/pairs. `done(finished)` after each pair, never from two threads at once.
PairRegistrationOutcome RegisterPairs(const std::vector<AcquisitionNode>& nodes,
                                      const std::vector<NeighbourPair>& pairs, const Rig& rig,
                                      const std::filesystem::path& rgbd_folder,
                                      const std::filesystem::path& pairs_folder,
                                      const PairRegistrationOptions& options, int threads,
                                      const std::function<void(int)>& done);

/// The edge of a pair record (none when its method is "none"), with the between-modules floor
/// where the two acquisitions are of different modules; information that is not symmetric
/// positive definite (a frozen direction exactly zero) gets a vanishing floor (σ 1 m, 10 rad)
/// so that the solver accepts it.
std::optional<RegistrationEdge> PairEdge(const PairRecord& record, const NeighbourPair& pair,
                                         const PairRegistrationOptions& options);

}  // namespace sewer3d
