#include "sewer3d/register/fusion.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;
// Information of a zero sum of biases (BiasGroups): σ 0.005 mm and 0.001° — held, not weighed.
const Matrix6d kZeroSum = (Vector6d() << Eigen::Vector3d::Constant(1.0 / (0.005 * 0.005)),
                           Eigen::Vector3d::Constant(std::pow(0.001 / kRadToDeg, -2)))
                              .finished()
                              .asDiagonal();

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

using GroupKey = std::tuple<int, int, int, int>;  // type, module a, module b, counter step

// The edges that share a bias: per edge its group (or −1), each group's key, and the families
// of groups whose biases sum to zero. Groups are of feature edges only: projection edges are
// few per group and degenerate on a plain cylinder (a bias there would fill the directions
// their information leaves open). A family: the registrations of each module with itself at one
// counter step (the along pairs). Their common part, in the carrier's frame, is the carrier's
// motion itself (its speed; a turn of every module alike: the "bent pipe"), which only the
// odometry and the straightness prior could tell from a bias; the modules' calibrations err
// independently, so their mean is taken as zero. Each bias is turned from its camera's frame
// into the model frame by the camera's initial orientation.
struct BiasGroups {
  std::vector<int> of_edge;
  std::vector<GroupKey> keys;
  std::vector<Matrix6d> priors;  ///< per group: the information of its zero-mean prior
  std::vector<BiasSum> zero_sums;
};

// The residual's frame (camera a's: translation and rotation vector) into the model frame.
Matrix6d ModelFromCamera(const AcquisitionNode& a) {
  const Eigen::Matrix3d r = a.world_from_camera.RotationMatrix();
  Matrix6d m = Matrix6d::Zero();
  m.topLeftCorner<3, 3>() = r;
  m.bottomRightCorner<3, 3>() = r;
  return m;
}

// Less counted travel than this over a module's odometry edges: no scale group (the mean
// step would have no direction).
constexpr double kMinScaleTravelMm = 1.0;

// The prior of a module's odometry bias: along its steps σ = odometry_scale_sigma × the mean
// step, nothing else (a counter errs in distance only).
Matrix6d OdometryScalePrior(const std::vector<RegistrationEdge>& edges,
                            const std::vector<size_t>& list, const FusionOptions& options) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (size_t k : list) sum += edges[k].a_from_b.translation;
  const double step = sum.norm() / static_cast<double>(list.size());
  const Eigen::Vector3d u = sum.normalized();
  const Eigen::Matrix3d along = u * u.transpose();
  constexpr double kHeld = 1e6;  // σ 1 µm / 1 µrad: the other components stay zero
  Matrix6d prior = Matrix6d::Identity() * kHeld;
  prior.topLeftCorner<3, 3>() = along * std::pow(options.odometry_scale_sigma * step, -2) +
                                (Eigen::Matrix3d::Identity() - along) * kHeld;
  prior.bottomRightCorner<3, 3>() = Eigen::Matrix3d::Identity() * kHeld * kHeld;
  return prior;
}

// Each module's odometry edges (at least min_bias_edges) as one group whose bias is the cable
// counter's scale error along the steps: what feature edges measure of the true distance fixes
// it, and it corrects the steps where nothing else sees the distance (plastic). No zero sum:
// the scale error is common to every module by nature.
void AddOdometryGroups(const std::vector<AcquisitionNode>& nodes,
                       const std::vector<RegistrationEdge>& edges, const FusionOptions& options,
                       BiasGroups& groups) {
  std::map<int, std::vector<size_t>> per_module;
  for (size_t k = 0; k < edges.size(); ++k) {
    if (edges[k].type == RegistrationEdgeType::kOdometry &&
        nodes[edges[k].a].module == nodes[edges[k].b].module)
      per_module[nodes[edges[k].a].module].push_back(k);
  }
  for (const auto& [module, list] : per_module) {
    if (static_cast<int>(list.size()) < options.min_bias_edges) continue;
    // A carrier that stood still (no distance counted) has no direction for a scale error.
    Eigen::Vector3d travel = Eigen::Vector3d::Zero();
    for (size_t k : list) travel += edges[k].a_from_b.translation;
    if (travel.norm() < kMinScaleTravelMm) continue;
    const int g = static_cast<int>(groups.keys.size());
    for (size_t k : list) groups.of_edge[k] = g;
    groups.keys.emplace_back(static_cast<int>(RegistrationEdgeType::kOdometry), module, module, 1);
    groups.priors.push_back(OdometryScalePrior(edges, list, options));
  }
}

BiasGroups FindBiasGroups(const std::vector<AcquisitionNode>& nodes,
                          const std::vector<RegistrationEdge>& edges, const FusionOptions& options,
                          const Matrix6d& prior) {
  BiasGroups groups;
  groups.of_edge.assign(edges.size(), -1);
  if (options.odometry_scale) AddOdometryGroups(nodes, edges, options, groups);
  if (!options.group_biases) return groups;
  std::map<GroupKey, std::vector<size_t>> members;
  for (size_t k = 0; k < edges.size(); ++k) {
    const RegistrationEdge& e = edges[k];
    if (e.type != RegistrationEdgeType::kFeature) continue;
    members[{static_cast<int>(e.type), nodes[e.a].module, nodes[e.b].module,
             nodes[e.b].counter - nodes[e.a].counter}]
        .push_back(k);
  }
  std::map<std::pair<int, int>, BiasSum> along;  // type, counter step
  for (const auto& [key, list] : members) {
    if (static_cast<int>(list.size()) < options.min_bias_edges) continue;
    const int g = static_cast<int>(groups.keys.size());
    for (size_t k : list) groups.of_edge[k] = g;
    groups.keys.push_back(key);
    groups.priors.push_back(prior);
    const auto& [type, module_a, module_b, step] = key;
    if (module_a != module_b) continue;
    BiasSum& family = along[{type, step}];
    family.groups.push_back(g);
    family.frames.push_back(ModelFromCamera(nodes[edges[list.front()].a]));
    family.information = kZeroSum;
  }
  for (auto& [family, sum] : along) groups.zero_sums.push_back(std::move(sum));
  return groups;
}

/// The inclinometer's direction of gravity at every node that has it, and the world's (the
/// graph's common direction, carried from one solve to the next).
struct Gravity {
  std::vector<DirectionObservation> observations;
  Eigen::Vector3d world = Eigen::Vector3d::UnitY();
};

// One observation per node with down_in_camera; the nodes of one counter read the same sensor,
// so each weighs 1/count of one reading (σ · √count).
Gravity GravityObservations(const std::vector<AcquisitionNode>& nodes,
                            const FusionOptions& options) {
  Gravity gravity;
  if (!options.gravity) return gravity;
  std::map<int, int> per_counter;
  for (const AcquisitionNode& node : nodes)
    per_counter[node.counter] += node.down_in_camera ? 1 : 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
    const AcquisitionNode& node = nodes[i];
    if (!node.down_in_camera) continue;
    const double sigma =
        options.gravity_sigma_deg / kRadToDeg * std::sqrt(per_counter.at(node.counter));
    gravity.observations.push_back({i, *node.down_in_camera, sigma});
    sum += node.world_from_camera.rotation * *node.down_in_camera;
  }
  if (!gravity.observations.empty()) gravity.world = sum.normalized();
  return gravity;
}

/// What the graph holds besides its edges: the gravity observations and the centreline.
struct Observations {
  Gravity gravity;
  std::optional<CentrelineSetup> centreline;
};

/// The graph of the accepted edges at the given poses (node 0 fixed), each group's edges
/// sharing its bias (starting at `bias`, under its group's prior), with the observations.
PoseGraph BuildGraph(const std::vector<Rigid3d>& poses, const std::vector<RegistrationEdge>& edges,
                     const std::vector<bool>& accepted, double huber_delta,
                     const BiasGroups& groups, const std::vector<Vector6d>& bias,
                     const Observations& seen) {
  PoseGraph graph;
  for (int i = 0; i < static_cast<int>(poses.size()); ++i) graph.SetNode(i, poses[i]);
  const Gravity& gravity = seen.gravity;
  if (!gravity.observations.empty()) graph.SetWorldDirection(gravity.world);
  for (const DirectionObservation& d : gravity.observations) graph.AddDirection(d);
  if (seen.centreline) {
    graph.SetAxisCurve(seen.centreline->curve);
    for (const AxisObservation& o : seen.centreline->observations) graph.AddAxisObservation(o);
  }
  for (size_t g = 0; g < groups.keys.size(); ++g)
    graph.SetBias(static_cast<int>(g), EdgeBias{bias[g], groups.priors[g]});
  for (const BiasSum& family : groups.zero_sums) graph.AddZeroSum(family);
  for (size_t k = 0; k < edges.size(); ++k) {
    if (!accepted[k]) continue;
    PoseEdge e = ToPoseEdge(edges[k], huber_delta);
    e.bias = groups.keys.empty() ? -1 : groups.of_edge[k];
    graph.AddEdge(e);
  }
  graph.fixed_nodes() = {0};
  return graph;
}

std::vector<Vector6d> Biases(const PoseGraph& graph, size_t count) {
  std::vector<Vector6d> bias(count);
  for (size_t g = 0; g < count; ++g) bias[g] = graph.biases().at(static_cast<int>(g)).value;
  return bias;
}

// The measurement whose residual is smaller by `bias` (translation: p̂ + b_t; rotation: the
// residual 2 vec(q̂ q⁻¹) is about the rotation vector, so q̂ turns by −b_r first).
Rigid3d Corrected(const Rigid3d& a_from_b, const Vector6d& bias) {
  Rigid3d c = a_from_b;
  c.translation += bias.head<3>();
  const Eigen::Vector3d turn = -bias.tail<3>();
  if (const double angle = turn.norm(); angle > 0.0) {
    c.rotation =
        (Eigen::Quaterniond(Eigen::AngleAxisd(angle, turn / angle)) * c.rotation).normalized();
  }
  return c;
}

// The edges with their groups' biases taken out of the measurements.
std::vector<RegistrationEdge> Corrected(std::vector<RegistrationEdge> edges,
                                        const BiasGroups& groups,
                                        const std::vector<Vector6d>& bias) {
  for (size_t k = 0; k < edges.size(); ++k) {
    if (const int g = groups.of_edge[k]; g >= 0)
      edges[k].a_from_b = Corrected(edges[k].a_from_b, bias[g]);
  }
  return edges;
}

std::vector<Rigid3d> Poses(const PoseGraph& graph, size_t count) {
  std::vector<Rigid3d> poses(count);
  for (size_t i = 0; i < count; ++i) poses[i] = graph.node(static_cast<int>(i));
  return poses;
}

// The stations the feature edges span: there the texture sees the pipe's turn.
std::vector<StationSpan> TexturedSpans(const std::vector<AcquisitionNode>& nodes,
                                       const std::vector<RegistrationEdge>& edges) {
  std::vector<StationSpan> spans;
  for (const RegistrationEdge& e : edges) {
    if (e.type != RegistrationEdgeType::kFeature) continue;
    const double a = nodes[e.a].distance_mm, b = nodes[e.b].distance_mm;
    spans.push_back({std::min(a, b), std::max(a, b)});
  }
  return spans;
}

// After a solve: the world direction and the curve as solved, the stations re-associated.
void Update(const PoseGraph& graph, const std::vector<Rigid3d>& poses, Observations& seen) {
  seen.gravity.world = graph.world_direction();
  if (!seen.centreline) return;
  seen.centreline->curve = *graph.axis_curve();
  ReassociateStations(*seen.centreline, poses);
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

void GravityStatistics(const PoseGraph& graph, FusionReport& report) {
  report.gravity.observations = static_cast<int>(graph.directions().size());
  if (graph.directions().empty()) return;
  report.gravity.down_in_model = graph.world_direction();
  double sum = 0.0;
  for (const DirectionObservation& d : graph.directions()) {
    const Eigen::Vector3d seen = graph.node(d.node).rotation * d.in_node;
    const double angle =
        std::atan2(seen.cross(graph.world_direction()).norm(), seen.dot(graph.world_direction()));
    sum += angle * angle;
    report.gravity.max_deg = std::max(report.gravity.max_deg, angle * kRadToDeg);
  }
  report.gravity.rms_deg =
      std::sqrt(sum / static_cast<double>(graph.directions().size())) * kRadToDeg;
}

}  // namespace

void FusionOptions::Check() const {
  ValidatePositive("huber_delta", huber_delta);
  ValidatePositive("gate_chi2", gate_chi2);
  SEWER3D_VALIDATE(max_gate_rounds >= 1, "max_gate_rounds", "must be ≥ 1, got " << max_gate_rounds);
  SEWER3D_VALIDATE(max_iterations >= 1, "max_iterations", "must be ≥ 1, got " << max_iterations);
  SEWER3D_VALIDATE(threads >= 1, "threads", "must be ≥ 1, got " << threads);
  SEWER3D_VALIDATE(max_certify_nodes >= 0, "max_certify_nodes", "must be ≥ 0");
  SEWER3D_VALIDATE(min_bias_edges >= 1, "min_bias_edges", "must be ≥ 1, got " << min_bias_edges);
  ValidatePositive("bias_sigma_mm", bias_sigma_mm);
  ValidatePositive("bias_sigma_deg", bias_sigma_deg);
  ValidatePositive("gravity_sigma_deg", gravity_sigma_deg);
  ValidatePositive("odometry_scale_sigma", odometry_scale_sigma);
  centreline.Check();
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
  Vector6d prior;
  prior << Eigen::Vector3d::Constant(std::pow(options.bias_sigma_mm, -2)),
      Eigen::Vector3d::Constant(std::pow(options.bias_sigma_deg / kRadToDeg, -2));
  const BiasGroups groups = FindBiasGroups(nodes, edges, options, prior.asDiagonal());
  std::vector<Vector6d> bias(groups.keys.size(), Vector6d::Zero());

  PoseGraphOptions solve;
  solve.init = PoseGraphInit::kGiven;
  solve.max_iterations = options.max_iterations;
  solve.num_threads = options.threads;
  Observations seen{GravityObservations(nodes, options),
                    MakeCentreline(nodes, TexturedSpans(nodes, edges), options.centreline)};
  PoseGraph graph =
      BuildGraph(poses, edges, result.accepted, options.huber_delta, groups, bias, seen);
  result.report.first_solve = OptimisePoseGraph(graph, solve);
  poses = Poses(graph, nodes.size());
  bias = Biases(graph, bias.size());
  Update(graph, poses, seen);

  // Gate, then least squares on what is left, until the gate rejects nothing more.
  for (int round = 0; round < options.max_gate_rounds; ++round) {
    const std::vector<RegistrationEdge> corrected = Corrected(edges, groups, bias);
    int rejected_now = 0;
    for (size_t k = 0; k < edges.size(); ++k) {
      const Vector6d r = Residual(corrected[k], poses);
      result.chi2[k] = r.dot(edges[k].information * r);
      if (result.accepted[k] && IsRobustEdge(edges[k].type) && result.chi2[k] > options.gate_chi2) {
        result.accepted[k] = false;
        ++rejected_now;
      }
    }
    if (round > 0 && rejected_now == 0) break;
    result.report.rejected += rejected_now;
    ++result.report.gate_rounds;
    graph = BuildGraph(poses, edges, result.accepted, 0.0, groups, bias, seen);
    result.report.final_solve = OptimisePoseGraph(graph, solve);
    poses = Poses(graph, nodes.size());
    bias = Biases(graph, bias.size());
    Update(graph, poses, seen);
  }
  // The biases go into the measurements: what is left is a pose graph (written as graph.g2o),
  // and the certificate applies to it.
  result.edges = Corrected(edges, groups, bias);
  graph = BuildGraph(poses, result.edges, result.accepted, 0.0, BiasGroups{}, {}, seen);
  if (options.certify && n <= options.max_certify_nodes && n > 1) {
    solve.certify = true;
    result.report.final_solve = OptimisePoseGraph(graph, solve);
    poses = Poses(graph, nodes.size());
    Update(graph, poses, seen);
  }
  for (size_t k = 0; k < edges.size(); ++k) {
    const Vector6d r = Residual(result.edges[k], poses);
    result.chi2[k] = r.dot(edges[k].information * r);
  }
  result.report.usable = result.report.first_solve.usable && result.report.final_solve.usable;
  Statistics(result.edges, poses, result);
  GravityStatistics(graph, result.report);
  for (size_t g = 0; g < groups.keys.size(); ++g) {
    EdgeGroupBias b;
    b.type = static_cast<RegistrationEdgeType>(std::get<0>(groups.keys[g]));
    b.module_a = std::get<1>(groups.keys[g]);
    b.module_b = std::get<2>(groups.keys[g]);
    b.counter_step = std::get<3>(groups.keys[g]);
    for (size_t k = 0; k < edges.size(); ++k)
      b.edges += groups.of_edge[k] == static_cast<int>(g) && result.accepted[k];
    b.bias = bias[g];
    result.report.biases.push_back(b);
  }
  if (seen.centreline) {
    result.report.centreline = ReportCentreline(*seen.centreline, poses);
    result.centreline = seen.centreline->curve;
  }
  result.world_from_camera = std::move(poses);
  result.graph = std::move(graph);
  return result;
}

}  // namespace sewer3d
