#pragma once
/// \file
/// A 3D pose graph (paper §optimise): nodes are absolute poses (world_from_node, position +
/// unit quaternion), edges are measured relative poses with 6x6 information matrices in the
/// order (translation, rotation). Plain data; the solver is in solver.hpp.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <map>
#include <optional>
#include <vector>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/posegraph/axis_curve.hpp"

namespace sewer3d {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Where an edge comes from; the paper weighs feature edges above projection edges and adds
/// regularisation edges between the first and last acquisition of each module.
enum class EdgeKind { kGeneric, kOdometry, kFeature, kProjection, kRegularisation };

struct PoseEdge {
  int from = 0;  ///< node a
  int to = 0;    ///< node b
  /// Measured pose of b in a's frame: p̂_ab = R_aᵀ (p_b − p_a), q̂_ab = q_a⁻¹ q_b.
  Rigid3d a_from_b;
  /// Information of the residual [translation; 2 vec(rotation error)]; symmetric positive
  /// definite.
  Matrix6d information = Matrix6d::Identity();
  EdgeKind kind = EdgeKind::kGeneric;
  /// Huber scale for this edge's residual norm (<= 0: plain least squares).
  double huber_delta = 0.0;
  /// The group (PoseGraph::biases()) whose bias b this edge's measurement shares: the residual
  /// becomes r − b; −1: none.
  int bias = -1;
};

/// A bias shared by a group of edges (one sensor's systematic error, e.g. every registration
/// between the same two modules): estimated with the poses under a zero-mean Gaussian prior.
struct EdgeBias {
  Eigen::Matrix<double, 6, 1> value = Eigen::Matrix<double, 6, 1>::Zero();
  Matrix6d prior_information = Matrix6d::Identity();  ///< SPD
};

/// Σ_k frames[k] · b(groups[k]) = 0, with `information` on the sum (PoseGraph::AddZeroSum).
struct BiasSum {
  std::vector<int> groups;
  std::vector<Matrix6d> frames;
  Matrix6d information = Matrix6d::Identity();
};

/// A direction measured in a node's own frame that points the same way in the world for every
/// observation of the graph, such as gravity from an inclinometer on the carrier: the residual
/// (R_world_from_node · in_node − g) / sigma_rad, with g the graph's world direction
/// (PoseGraph::world_direction), a unit vector estimated with the poses. It fixes a node's
/// tilt (two of its three angles) against all the others', whatever the edges say.
struct DirectionObservation {
  int node = 0;
  Eigen::Vector3d in_node = Eigen::Vector3d::UnitY();  ///< unit
  double sigma_rad = 1e-3;  ///< of each of the two angles across the direction
};

class PoseGraph {
 public:
  /// Adds or replaces node `id` (pose = world_from_node).
  void SetNode(int id, const Rigid3d& world_from_node) { nodes_[id] = world_from_node; }
  bool HasNode(int id) const { return nodes_.count(id) != 0; }
  const Rigid3d& node(int id) const { return nodes_.at(id); }
  Rigid3d& mutable_node(int id) { return nodes_.at(id); }
  const std::map<int, Rigid3d>& nodes() const { return nodes_; }

  /// Adds an edge; throws std::invalid_argument for unknown nodes, a self-loop, an
  /// information matrix that is not symmetric positive definite, or a bias group not set.
  void AddEdge(const PoseEdge& edge);

  /// Adds or replaces bias group `id` (std::invalid_argument: a prior that is not SPD).
  void SetBias(int id, const EdgeBias& bias);
  const std::map<int, EdgeBias>& biases() const { return biases_; }
  std::map<int, EdgeBias>& mutable_biases() { return biases_; }

  /// Biases whose sum Σ A_g b_g is known to be zero (e.g. the same kind of error of several
  /// sensors that err independently, each bias turned into a common frame by A_g), with this
  /// information on the sum: ½ (Σ A b)ᵀ Ω (Σ A b) joins the cost. std::invalid_argument: a
  /// group not set, sizes that differ, or information that is not SPD.
  void AddZeroSum(const BiasSum& sum);
  const std::vector<BiasSum>& zero_sums() const { return zero_sums_; }

  /// The paper's regularisation edge: "node b sits at a_from_b relative to node a" with the
  /// given 6x6 covariance (translation mm², rotation rad²), e.g. first and last acquisition
  /// of a module in a straight pipe.
  void AddRegularisationEdge(int a, int b, const Rigid3d& a_from_b, const Matrix6d& covariance);

  const std::vector<PoseEdge>& edges() const { return edges_; }
  std::vector<PoseEdge>& mutable_edges() { return edges_; }

  /// Adds a direction observation (std::invalid_argument: unknown node, a direction that is not
  /// a finite non-zero vector (it is normalised), or sigma_rad not > 0). The first one sets the
  /// world direction to where the node's pose puts it, unless SetWorldDirection came first.
  void AddDirection(const DirectionObservation& observation);
  const std::vector<DirectionObservation>& directions() const { return directions_; }
  /// The common world direction g of the direction observations (unit).
  const Eigen::Vector3d& world_direction() const { return world_direction_; }
  void SetWorldDirection(const Eigen::Vector3d& direction);

  /// The pipe's centreline, estimated with the poses (axis_curve.hpp). std::invalid_argument:
  /// fewer than 3 points, a spacing or a σ not > 0, or values that are not finite.
  void SetAxisCurve(const AxisCurve& centreline);
  const std::optional<AxisCurve>& axis_curve() const { return axis_curve_; }
  AxisCurve& mutable_axis_curve() { return *axis_curve_; }
  /// Adds an axis observation (std::invalid_argument: no centreline set, unknown node, values
  /// not finite, σ not > 0).
  void AddAxisObservation(const AxisObservation& observation);
  const std::vector<AxisObservation>& axis_observations() const { return axis_observations_; }
  std::vector<AxisObservation>& mutable_axis_observations() { return axis_observations_; }

  /// Nodes held fixed by the file or the caller (gauge); the solver also fixes the first node
  /// when this is empty.
  std::vector<int>& fixed_nodes() { return fixed_; }
  const std::vector<int>& fixed_nodes() const { return fixed_; }

 private:
  std::map<int, Rigid3d> nodes_;
  std::vector<PoseEdge> edges_;
  std::vector<int> fixed_;
  std::map<int, EdgeBias> biases_;
  std::vector<BiasSum> zero_sums_;
  std::vector<DirectionObservation> directions_;
  Eigen::Vector3d world_direction_ = Eigen::Vector3d::UnitY();
  bool world_direction_set_ = false;
  std::optional<AxisCurve> axis_curve_;
  std::vector<AxisObservation> axis_observations_;
};

/// (R_world_from_node · in_node − g) / sigma_rad of one observation at the given pose.
Eigen::Vector3d DirectionResidual(const DirectionObservation& observation,
                                  const Rigid3d& world_from_node,
                                  const Eigen::Vector3d& world_direction);

/// The residual of one edge at the given poses (Ceres' pose_graph_3d convention):
/// r = [R_aᵀ (p_b − p_a) − p̂_ab ; 2 vec(q̂_ab (q_a⁻¹ q_b)⁻¹)].
Eigen::Matrix<double, 6, 1> EdgeResidual(const PoseEdge& edge, const Rigid3d& world_from_a,
                                         const Rigid3d& world_from_b);

/// ½ Σ rᵀ Ω r over all edges (no robust loss): the cost convention of Ceres' example and of
/// the published benchmark values.
/// ½ Σ rᵀΩr, with r − b for edges of a bias group, plus ½ Σ bᵀ P b of the biases' priors, the
/// zero sums' terms, ½ Σ |r|² of the direction and axis observations and of the centreline's
/// curvature terms.
double GraphCost(const PoseGraph& graph);

/// GraphCost with every edge's measurement inverted (b_from_a in place of a_from_b): far below
/// GraphCost when the edges were written with from and to swapped.
double GraphCostEdgesInverted(const PoseGraph& graph);

/// An edge whose χ² (rᵀ Ω r at the graph's poses) stands out from the others'.
struct OutlierEdge {
  std::size_t index = 0;  ///< in graph.edges()
  double chi2 = 0.0;
  double median_chi2 = 0.0;  ///< over all edges
};

/// The edge of largest χ² when it is over `min_chi2` and over `factor` times the median edge's
/// (the median taken as at least 1): one measurement the others contradict, such as an edge in
/// other units or a false loop closure. With Gaussian noise the largest of 10⁵ edges is about
/// 8 times the median. nullopt when none stands out or there are fewer than 3 edges.
std::optional<OutlierEdge> FindOutlierEdge(const PoseGraph& graph, double factor = 100.0,
                                           double min_chi2 = 1000.0);

/// True when `m` is symmetric (to 1e-9 relative) and positive definite.
bool IsSymmetricPositiveDefinite(const Matrix6d& m);

}  // namespace sewer3d
