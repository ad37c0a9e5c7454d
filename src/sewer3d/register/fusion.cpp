#include "sewer3d/register/fusion.hpp"

#include <algorithm>
#include <cmath>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

EdgeKind KindOf(RegistrationEdgeType type) {
  switch (type) {
    case RegistrationEdgeType::kFeature:
      return EdgeKind::kFeature;
    case RegistrationEdgeType::kProjection:
      return EdgeKind::kProjection;
    case RegistrationEdgeType::kOdometry:
      return EdgeKind::kOdometry;
    case RegistrationEdgeType::kStraightness:
      return EdgeKind::kRegularisation;
    case RegistrationEdgeType::kRig:
      return EdgeKind::kGeneric;
  }
  return EdgeKind::kGeneric;
}

// Edges that may be wrong: the pairwise registrations, and the odometry, whose cable slips
// (a counter that runs on while the robot stands, or the reverse) contradict what the images
// say. The robust loss and the gate apply to them; rig and straightness edges are priors.
bool IsRobustEdge(RegistrationEdgeType type) {
  return IsPairwiseEdge(type) || type == RegistrationEdgeType::kOdometry;
}

PoseEdge ToPoseEdge(const RegistrationEdge& e, double huber_delta) {
  PoseEdge p;
  p.from = e.a;
  p.to = e.b;
  p.a_from_b = e.a_from_b;
  p.information = e.information;
  p.kind = KindOf(e.type);
  p.huber_delta = IsRobustEdge(e.type) ? huber_delta : 0.0;
  return p;
}

/// The graph of the accepted edges at the given poses (node 0 fixed).
PoseGraph BuildGraph(const std::vector<Rigid3d>& poses, const std::vector<RegistrationEdge>& edges,
                     const std::vector<bool>& accepted, double huber_delta) {
  PoseGraph graph;
  for (int i = 0; i < static_cast<int>(poses.size()); ++i) graph.SetNode(i, poses[i]);
  for (size_t k = 0; k < edges.size(); ++k) {
    if (accepted[k]) graph.AddEdge(ToPoseEdge(edges[k], huber_delta));
  }
  graph.fixed_nodes() = {0};
  return graph;
}

std::vector<Rigid3d> Poses(const PoseGraph& graph, size_t count) {
  std::vector<Rigid3d> poses(count);
  for (size_t i = 0; i < count; ++i) poses[i] = graph.node(static_cast<int>(i));
  return poses;
}

Vector6d Residual(const RegistrationEdge& e, const std::vector<Rigid3d>& poses) {
  PoseEdge p;
  p.a_from_b = e.a_from_b;
  return EdgeResidual(p, poses[e.a], poses[e.b]);
}

void Statistics(const std::vector<RegistrationEdge>& edges, const std::vector<Rigid3d>& poses,
                FusionResult& result) {
  std::array<std::vector<double>, kRegistrationEdgeTypes> chi2s;
  for (size_t k = 0; k < edges.size(); ++k) {
    const int t = static_cast<int>(edges[k].type);
    EdgeTypeStatistics& s = result.report.by_type[t];
    ++s.edges;
    if (!result.accepted[k]) continue;
    ++s.accepted;
    const Vector6d r = Residual(edges[k], poses);
    s.rms_translation_mm += r.head<3>().squaredNorm();
    s.rms_rotation_deg += r.tail<3>().squaredNorm();
    chi2s[t].push_back(result.chi2[k]);
  }
  for (int t = 0; t < kRegistrationEdgeTypes; ++t) {
    EdgeTypeStatistics& s = result.report.by_type[t];
    std::vector<double>& v = chi2s[t];
    if (v.empty()) continue;
    s.rms_translation_mm = std::sqrt(s.rms_translation_mm / s.accepted);
    s.rms_rotation_deg = std::sqrt(s.rms_rotation_deg / s.accepted) * kRadToDeg;
    std::sort(v.begin(), v.end());
    s.median_chi2 = v[v.size() / 2];
    s.max_chi2 = v.back();
    for (double x : v) s.mean_chi2 += x / static_cast<double>(v.size());
  }
}

}  // namespace

void FusionOptions::Check() const {
  ValidatePositive("huber_delta", huber_delta);
  ValidatePositive("gate_chi2", gate_chi2);
  SEWER3D_VALIDATE(max_gate_rounds >= 1, "max_gate_rounds", "must be ≥ 1, got " << max_gate_rounds);
  SEWER3D_VALIDATE(max_iterations >= 1, "max_iterations", "must be ≥ 1, got " << max_iterations);
  SEWER3D_VALIDATE(threads >= 1, "threads", "must be ≥ 1, got " << threads);
  SEWER3D_VALIDATE(max_certify_nodes >= 0, "max_certify_nodes", "must be ≥ 0");
}

FusionResult FuseRegistration(const std::vector<AcquisitionNode>& nodes,
                              const std::vector<RegistrationEdge>& edges,
                              const FusionOptions& options) {
  options.Check();
  SEWER3D_VALIDATE(!nodes.empty(), "nodes", "the graph needs at least one node");
  const int n = static_cast<int>(nodes.size());
  for (const RegistrationEdge& e : edges) {
    SEWER3D_VALIDATE(e.a >= 0 && e.a < n && e.b >= 0 && e.b < n && e.a != e.b, "edges",
                     "edge " << e.a << " → " << e.b << " with " << n << " nodes");
  }
  FusionResult result;
  result.accepted.assign(edges.size(), true);
  result.chi2.assign(edges.size(), 0.0);
  std::vector<Rigid3d> poses;
  for (const AcquisitionNode& node : nodes) poses.push_back(node.world_from_camera);

  PoseGraphOptions solve;
  solve.init = PoseGraphInit::kGiven;
  solve.max_iterations = options.max_iterations;
  solve.num_threads = options.threads;
  PoseGraph graph = BuildGraph(poses, edges, result.accepted, options.huber_delta);
  result.report.first_solve = OptimisePoseGraph(graph, solve);
  poses = Poses(graph, nodes.size());

  // Gate, then least squares on what is left, until the gate rejects nothing more.
  for (int round = 0; round < options.max_gate_rounds; ++round) {
    int rejected_now = 0;
    for (size_t k = 0; k < edges.size(); ++k) {
      const Vector6d r = Residual(edges[k], poses);
      result.chi2[k] = r.dot(edges[k].information * r);
      if (result.accepted[k] && IsRobustEdge(edges[k].type) && result.chi2[k] > options.gate_chi2) {
        result.accepted[k] = false;
        ++rejected_now;
      }
    }
    if (round > 0 && rejected_now == 0) break;
    result.report.rejected += rejected_now;
    ++result.report.gate_rounds;
    graph = BuildGraph(poses, edges, result.accepted, 0.0);
    solve.certify = false;
    result.report.final_solve = OptimisePoseGraph(graph, solve);
    poses = Poses(graph, nodes.size());
  }
  // The certificate of the final (least-squares) graph.
  if (options.certify && n <= options.max_certify_nodes && n > 1) {
    solve.certify = true;
    result.report.final_solve = OptimisePoseGraph(graph, solve);
    poses = Poses(graph, nodes.size());
  }
  for (size_t k = 0; k < edges.size(); ++k) {
    const Vector6d r = Residual(edges[k], poses);
    result.chi2[k] = r.dot(edges[k].information * r);
  }
  result.report.usable = result.report.first_solve.usable && result.report.final_solve.usable;
  Statistics(edges, poses, result);
  result.world_from_camera = std::move(poses);
  result.graph = std::move(graph);
  return result;
}

}  // namespace sewer3d
