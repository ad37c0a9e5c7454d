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
///
/// Biases shared by a group of pairwise edges (`group_biases`): a module's calibration error
/// distorts every depth map it makes in the same way, so every registration between the same
/// two modules at the same counter step errs alike (on the full-size demo, the along edges of
/// one module by up to 0.19 mm and 0.06° with a spread of a tenth of that). Independent
/// weights cannot average such an error away; the graph bends to it. So each group of feature
/// edges (module of a, module of b, counter of b − counter of a) of at least `min_bias_edges`
/// edges shares a bias b, subtracted from its edges' residuals (r − b) and estimated with the
/// poses in every solve, under a zero-mean prior (`bias_sigma_mm`, `bias_sigma_deg` per axis).
/// What the rig, the odometry and the other groups agree on decides. The along groups (a module
/// with itself at one counter step) are held to a zero sum in the model frame: their common
/// part is the carrier's own motion (speed, a turn of all modules alike: the "bent pipe"), which
/// a bias must not take. The biases are then taken out of the measurements (`edges` of the
/// result, graph.g2o) and the certificate, where enabled, judges that pose graph.
///
/// The pipe's centreline (fusion_centreline.hpp, `centreline`): each node's axis point tied to
/// one curve whose bend costs, weakly where feature edges see the pipe's turn and strongly
/// where none do.
///
/// What the zero sum keeps, a turn every module's along edges share (a common part of the
/// modules' calibration errors), bends the model, and only an absolute reference can tell it
/// from a bent pipe: the inclinometer's direction of gravity at every acquisition
/// (`gravity`), a direction observation whose world direction is estimated with the poses (so
/// the pipe's gradient is free and a constant tilt of the sensor is absorbed).

#include <array>
#include <string>
#include <vector>

#include "sewer3d/posegraph/solver.hpp"
#include "sewer3d/register/fusion_centreline.hpp"
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
  bool group_biases = true;     ///< estimate the biases of groups of pairwise edges
  int min_bias_edges = 4;       ///< a group of fewer edges keeps its measurements
  double bias_sigma_mm = 0.5;   ///< prior σ of a group's bias, translation (per axis)
  double bias_sigma_deg = 0.2;  ///< and rotation
  /// The inclinometer (AcquisitionNode::down_in_camera): each instant's direction of gravity
  /// as a direction observation of its nodes (PoseGraph::AddDirection) with this σ per reading
  /// (shared by the instant's nodes). It holds the carrier's pitch and roll where a turn every
  /// registration shares would bend the model. The certificate does not apply then.
  bool gravity = true;
  double gravity_sigma_deg = 0.05;
  /// The cable counter's scale error: each module's odometry edges share a bias along their
  /// steps (prior σ odometry_scale_sigma of a step), fixed where feature edges see the true
  /// distance and carried to where nothing else does (plastic).
  bool odometry_scale = true;
  double odometry_scale_sigma = 0.01;
  /// The pipe's centreline (fusion_centreline.hpp) from the nodes' axis points.
  CentrelineOptions centreline;

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

/// The bias taken out of one group of pairwise edges (see the file comment).
struct EdgeGroupBias {
  RegistrationEdgeType type = RegistrationEdgeType::kFeature;
  int module_a = 0, module_b = 0, counter_step = 0;
  int edges = 0;  ///< accepted at the end
  /// Subtracted from the residual: translation (mm, camera a's frame), rotation vector (rad).
  Eigen::Matrix<double, 6, 1> bias = Eigen::Matrix<double, 6, 1>::Zero();
};

/// The inclinometer's part in the fusion (FusionOptions::gravity).
struct GravityReport {
  int observations = 0;  ///< nodes with a direction of gravity
  /// Where the fused poses put gravity: its angle to the common direction, over the nodes.
  double rms_deg = 0.0, max_deg = 0.0;
  /// The common direction in the model frame (its z component: the pipe's gradient, sin).
  Eigen::Vector3d down_in_model = Eigen::Vector3d::Zero();
};

struct FusionReport {
  PoseGraphReport first_solve;  ///< with the robust loss
  PoseGraphReport final_solve;  ///< least squares on the accepted edges (+ certificate)
  int gate_rounds = 0;
  int rejected = 0;  ///< pairwise edges rejected by the gate
  std::array<EdgeTypeStatistics, kRegistrationEdgeTypes> by_type{};
  bool usable = false;                ///< both solves usable
  std::vector<EdgeGroupBias> biases;  ///< groups whose measurements were corrected
  GravityReport gravity;
  std::optional<CentrelineReport> centreline;  ///< where the graph had one
};

struct FusionResult {
  std::vector<Rigid3d> world_from_camera;  ///< per node, model frame
  /// The edges as fused: the given ones, with the group biases taken out of the measurements.
  std::vector<RegistrationEdge> edges;
  std::vector<double> chi2;    ///< per edge, rᵀΩr at the final poses
  std::vector<bool> accepted;  ///< per edge
  PoseGraph graph;             ///< as optimised: node id = node index, the accepted edges in order
  std::optional<AxisCurve> centreline;  ///< as estimated (model frame), where there was one
  FusionReport report;
};

/// Builds and solves the graph. Throws std::invalid_argument for bad options, no nodes, or an
/// edge naming a node out of range or with information that is not SPD.
FusionResult FuseRegistration(const std::vector<AcquisitionNode>& nodes,
                              const std::vector<RegistrationEdge>& edges,
                              const FusionOptions& options);

}  // namespace sewer3d
