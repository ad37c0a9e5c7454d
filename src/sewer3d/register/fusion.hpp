#pragma once
/// \file
/// Fusion of the registration graph (issue 15 item 6; paper §4.3): nodes are acquisitions at
/// their initial poses, edges the pairwise registrations (feature, projection) and the prior
/// edges (rig, odometry, straightness, prior_edges.hpp), weighted by their information.
///
/// 1. Levenberg–Marquardt with a Huber loss on the pairwise and the odometry edges (scale
///    `huber_delta` on the Mahalanobis length √(rᵀΩr)), so that an outlier pulls with bounded
///    force: a wrong registration, or the cable counter slipping;
/// 2. χ² gate: such an edge whose rᵀΩr at that solution exceeds the 6-DoF χ² quantile
///    (99.9 %: 22.46) is rejected; the rest are solved again by plain least squares (no robust
///    loss, so the information weights hold), gating again until no edge is rejected;
/// 3. the certificate (posegraph/certificate.hpp) on the last graph, where enabled.
/// The first node is held fixed: it keeps the model frame of the initial poses.

#include <array>
#include <string>
#include <vector>

#include "sewer3d/posegraph/solver.hpp"
#include "sewer3d/register/prior_edges.hpp"

namespace sewer3d {

struct FusionOptions {
  double huber_delta = 3.0;   ///< Huber scale of the first solve, √χ² units (pairwise only)
  double gate_chi2 = 22.458;  ///< χ²(6) at 0.999
  int max_gate_rounds = 5;
  int max_iterations = 200;  ///< Levenberg–Marquardt, per solve
  int threads = 1;
  bool certify = true;          ///< run the certificate on the final graph
  int max_certify_nodes = 400;  ///< larger graphs are not certified (time)

  void Check() const;
};

/// Residual statistics of one edge type at the final poses.
struct EdgeTypeStatistics {
  int edges = 0;
  int accepted = 0;
  double median_chi2 = 0.0;  ///< rᵀΩr of the accepted edges
  double mean_chi2 = 0.0;
  double max_chi2 = 0.0;
  double rms_translation_mm = 0.0;  ///< of the residual's translation part, accepted edges
  double rms_rotation_deg = 0.0;    ///< of its rotation part (2 vec(q) ≈ angle)
};

struct FusionReport {
  PoseGraphReport first_solve;  ///< with the robust loss
  PoseGraphReport final_solve;  ///< least squares on the accepted edges (+ certificate)
  int gate_rounds = 0;
  int rejected = 0;  ///< pairwise edges rejected by the gate
  std::array<EdgeTypeStatistics, kRegistrationEdgeTypes> by_type{};
  bool usable = false;  ///< both solves usable
};

struct FusionResult {
  std::vector<Rigid3d> world_from_camera;  ///< per node, model frame
  std::vector<double> chi2;                ///< per edge, rᵀΩr at the final poses
  std::vector<bool> accepted;              ///< per edge
  PoseGraph graph;  ///< as optimised: node id = node index, the accepted edges in order
  FusionReport report;
};

/// Builds and solves the graph. Throws std::invalid_argument for bad options, no nodes, or an
/// edge naming a node out of range or with information that is not SPD.
FusionResult FuseRegistration(const std::vector<AcquisitionNode>& nodes,
                              const std::vector<RegistrationEdge>& edges,
                              const FusionOptions& options);

}  // namespace sewer3d
