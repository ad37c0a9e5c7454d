#include "sewer3d/posegraph/pose_graph.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

bool IsSymmetricPositiveDefinite(const Matrix6d& m) {
  if (!m.allFinite()) return false;
  if ((m - m.transpose()).norm() > 1e-9 * std::max(1.0, m.norm())) return false;
  const Eigen::LLT<Matrix6d> llt(m);
  return llt.info() == Eigen::Success;
}

void PoseGraph::AddEdge(const PoseEdge& edge) {
  SEWER3D_VALIDATE(HasNode(edge.from) && HasNode(edge.to), "",
                   "edge " << edge.from << " -> " << edge.to << " names a missing node");
  SEWER3D_VALIDATE(edge.from != edge.to, "", "self-loop on node " << edge.from);
  SEWER3D_VALIDATE(IsSymmetricPositiveDefinite(edge.information), "",
                   "information of edge " << edge.from << " -> " << edge.to
                                          << " is not symmetric positive definite");
  SEWER3D_VALIDATE(
      edge.a_from_b.translation.allFinite() && edge.a_from_b.rotation.coeffs().allFinite(), "",
      "edge " << edge.from << " -> " << edge.to << " has non-finite values");
  SEWER3D_VALIDATE(edge.bias < 0 || biases_.count(edge.bias) != 0, "",
                   "edge " << edge.from << " -> " << edge.to << " names bias group " << edge.bias
                           << ", which is not set");
  edges_.push_back(edge);
}

void PoseGraph::SetBias(int id, const EdgeBias& bias) {
  SEWER3D_VALIDATE(IsSymmetricPositiveDefinite(bias.prior_information), "",
                   "prior information of bias group " << id << " is not positive definite");
  SEWER3D_VALIDATE(bias.value.allFinite(), "", "bias group " << id << " has non-finite values");
  biases_[id] = bias;
}

void PoseGraph::AddRegularisationEdge(int a, int b, const Rigid3d& a_from_b,
                                      const Matrix6d& covariance) {
  SEWER3D_VALIDATE(IsSymmetricPositiveDefinite(covariance), "",
                   "covariance of edge " << a << " -> " << b << " is not positive definite");
  PoseEdge edge;
  edge.from = a;
  edge.to = b;
  edge.a_from_b = a_from_b;
  edge.information = covariance.inverse();
  edge.information = 0.5 * (edge.information + edge.information.transpose()).eval();
  edge.kind = EdgeKind::kRegularisation;
  AddEdge(edge);
}

void PoseGraph::AddZeroSum(const BiasSum& sum) {
  SEWER3D_VALIDATE(
      sum.groups.size() == sum.frames.size(), "",
      "a zero sum with " << sum.groups.size() << " groups and " << sum.frames.size() << " frames");
  for (int g : sum.groups) {
    SEWER3D_VALIDATE(biases_.count(g) != 0, "",
                     "zero sum names bias group " << g << ", which is not set");
  }
  SEWER3D_VALIDATE(IsSymmetricPositiveDefinite(sum.information), "",
                   "information of a zero sum is not positive definite");
  zero_sums_.push_back(sum);
}

void PoseGraph::AddDirection(const DirectionObservation& observation) {
  SEWER3D_VALIDATE(HasNode(observation.node), "",
                   "direction observation names missing node " << observation.node);
  SEWER3D_VALIDATE(observation.in_node.allFinite() && observation.in_node.norm() > 0.0, "",
                   "direction observation of node " << observation.node << " is not a direction");
  SEWER3D_VALIDATE(observation.sigma_rad > 0.0 && std::isfinite(observation.sigma_rad), "",
                   "direction observation of node " << observation.node << " has sigma "
                                                    << observation.sigma_rad);
  DirectionObservation o = observation;
  o.in_node.normalize();
  if (!world_direction_set_) SetWorldDirection(node(o.node).rotation * o.in_node);
  directions_.push_back(o);
}

void PoseGraph::SetWorldDirection(const Eigen::Vector3d& direction) {
  SEWER3D_VALIDATE(direction.allFinite() && direction.norm() > 0.0, "",
                   "world direction is not a direction");
  world_direction_ = direction.normalized();
  world_direction_set_ = true;
}

void PoseGraph::SetAxisCurve(const AxisCurve& centreline) {
  SEWER3D_VALIDATE(centreline.points.size() >= 3, "",
                   "a centreline needs 3 points, got " << centreline.points.size());
  SEWER3D_VALIDATE(centreline.spacing_mm > 0.0 && std::isfinite(centreline.start_station_mm), "",
                   "centreline spacing " << centreline.spacing_mm << " mm");
  SEWER3D_VALIDATE(centreline.curvature_sigma_mm.size() + 2 == centreline.points.size(), "",
                   "a centreline of " << centreline.points.size() << " points with "
                                      << centreline.curvature_sigma_mm.size() << " curvature σ");
  SEWER3D_VALIDATE(centreline.along_sigma_mm > 0.0, "", "centreline σ must be > 0");
  for (double sigma : centreline.curvature_sigma_mm)
    SEWER3D_VALIDATE(sigma > 0.0 && std::isfinite(sigma), "", "centreline σ must be > 0");
  for (const Eigen::Vector3d& p : centreline.points)
    SEWER3D_VALIDATE(p.allFinite(), "", "centreline point is not finite");
  axis_curve_ = centreline;
}

void PoseGraph::AddAxisObservation(const AxisObservation& observation) {
  SEWER3D_VALIDATE(axis_curve_.has_value(), "", "axis observation without a centreline");
  SEWER3D_VALIDATE(HasNode(observation.node), "",
                   "axis observation names missing node " << observation.node);
  SEWER3D_VALIDATE(observation.in_node.allFinite() && std::isfinite(observation.station_mm), "",
                   "axis observation of node " << observation.node << " is not finite");
  SEWER3D_VALIDATE(observation.sigma_mm > 0.0 && observation.along_sigma_mm > 0.0, "",
                   "axis observation of node " << observation.node << " has σ ≤ 0");
  axis_observations_.push_back(observation);
}

Eigen::Vector3d DirectionResidual(const DirectionObservation& observation,
                                  const Rigid3d& world_from_node,
                                  const Eigen::Vector3d& world_direction) {
  return (world_from_node.rotation * observation.in_node - world_direction) / observation.sigma_rad;
}

Eigen::Matrix<double, 6, 1> EdgeResidual(const PoseEdge& edge, const Rigid3d& world_from_a,
                                         const Rigid3d& world_from_b) {
  const Eigen::Quaterniond q_a_inverse = world_from_a.rotation.conjugate();
  const Eigen::Quaterniond q_ab = q_a_inverse * world_from_b.rotation;
  const Eigen::Quaterniond delta = edge.a_from_b.rotation * q_ab.conjugate();
  Eigen::Matrix<double, 6, 1> r;
  r.head<3>() = q_a_inverse * (world_from_b.translation - world_from_a.translation) -
                edge.a_from_b.translation;
  r.tail<3>() = (delta.w() < 0.0 ? -2.0 : 2.0) * delta.vec();
  return r;
}

double GraphCost(const PoseGraph& graph) {
  double cost = 0.0;
  for (const PoseEdge& e : graph.edges()) {
    auto r = EdgeResidual(e, graph.node(e.from), graph.node(e.to));
    if (e.bias >= 0) r -= graph.biases().at(e.bias).value;
    cost += 0.5 * r.dot(e.information * r);
  }
  for (const auto& [id, b] : graph.biases())
    cost += 0.5 * b.value.dot(b.prior_information * b.value);
  for (const BiasSum& z : graph.zero_sums()) {
    Eigen::Matrix<double, 6, 1> sum = Eigen::Matrix<double, 6, 1>::Zero();
    for (size_t k = 0; k < z.groups.size(); ++k)
      sum += z.frames[k] * graph.biases().at(z.groups[k]).value;
    cost += 0.5 * sum.dot(z.information * sum);
  }
  for (const DirectionObservation& d : graph.directions())
    cost += 0.5 * DirectionResidual(d, graph.node(d.node), graph.world_direction()).squaredNorm();
  if (const std::optional<AxisCurve>& c = graph.axis_curve()) {
    for (const AxisObservation& o : graph.axis_observations())
      cost += 0.5 * AxisResidual(o, graph.node(o.node), *c).squaredNorm();
    for (int k = 0; k + 2 < static_cast<int>(c->points.size()); ++k)
      cost += 0.5 * CurvatureResidual(*c, k).squaredNorm();
  }
  return cost;
}

double GraphCostEdgesInverted(const PoseGraph& graph) {
  double cost = 0.0;
  for (PoseEdge e : graph.edges()) {
    e.a_from_b = e.a_from_b.Inverse();
    const auto r = EdgeResidual(e, graph.node(e.from), graph.node(e.to));
    cost += 0.5 * r.dot(e.information * r);
  }
  return cost;
}

std::optional<OutlierEdge> FindOutlierEdge(const PoseGraph& graph, double factor, double min_chi2) {
  const std::vector<PoseEdge>& edges = graph.edges();
  if (edges.size() < 3) return std::nullopt;
  std::vector<double> chi2(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const PoseEdge& e = edges[i];
    const auto r = EdgeResidual(e, graph.node(e.from), graph.node(e.to));
    chi2[i] = r.dot(e.information * r);
  }
  const auto worst = std::max_element(chi2.begin(), chi2.end());
  OutlierEdge outlier{static_cast<std::size_t>(worst - chi2.begin()), *worst, 0.0};
  std::vector<double> sorted = chi2;
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), middle, sorted.end());
  outlier.median_chi2 = *middle;
  if (!(outlier.chi2 > min_chi2 && outlier.chi2 > factor * std::max(outlier.median_chi2, 1.0)))
    return std::nullopt;
  return outlier;
}

}  // namespace sewer3d
