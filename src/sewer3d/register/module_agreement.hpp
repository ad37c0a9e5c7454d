#pragma once
/// \file
/// Do the images agree with the rig? Registrations between two modules measure where one
/// camera sits relative to the other; the rig edges (prior_edges.hpp) hold them where rig.json
/// has them. When rig.json is wrong for a module (a translation in metres, a swapped clock
/// position) or two modules' image folders are swapped, the stiff rig edges win and the χ² gate
/// rejects the registrations between that module and its neighbours, nearly all of them, while
/// a chance outlier costs a pair one registration of many. This file counts, per pair of
/// modules, the pairwise edges and those the gate rejected, and how far apart the rejected
/// ones put the cameras at the fused poses; and the same for the registrations along the pipe,
/// which the odometry edges hold.

#include <vector>

#include "sewer3d/register/fusion.hpp"

namespace sewer3d {

struct ModulePairAgreement {
  int module_a = 0, module_b = 0;  ///< module_a < module_b
  int edges = 0;                   ///< feature and projection edges between the two
  int rejected = 0;                ///< of them, by the gate
  /// Median translation of the rejected edges' residuals at the fused poses (mm): how far the
  /// measurement puts camera b from where the graph has it; 0 when none is rejected.
  double median_rejected_offset_mm = 0.0;
};

/// One entry per pair of modules with at least one pairwise edge, ordered by (module_a,
/// module_b). `edges` and `fused` as FuseRegistration took and returned them for `nodes`.
/// Throws std::invalid_argument when `fused` does not match the edges or nodes.
std::vector<ModulePairAgreement> ModulePairAgreements(const std::vector<AcquisitionNode>& nodes,
                                                      const std::vector<RegistrationEdge>& edges,
                                                      const FusionResult& fused);

/// The registrations along the pipe (between acquisitions of one module), all modules
/// together, module_a = module_b = −1. The odometry edges predict them; when odometry.csv is in
/// other units (inches, a wrong scale) the gate rejects (nearly) all of them instead.
ModulePairAgreement AlongAgreement(const std::vector<AcquisitionNode>& nodes,
                                   const std::vector<RegistrationEdge>& edges,
                                   const FusionResult& fused);

/// True when the pair's registrations contradict the rig (or, along, the odometry): at
/// least `min_rejected` rejected, at least `min_fraction` of them, and `min_offset_mm` off (the
/// median). A sound simulated run (compact preset) has pairs with up to half of their
/// registrations rejected, about 1 mm off; a module 84 mm out rejects all of them, 84 mm off.
bool Disagrees(const ModulePairAgreement& pair, int min_rejected = 2, double min_fraction = 0.75,
               double min_offset_mm = 5.0);

}  // namespace sewer3d
