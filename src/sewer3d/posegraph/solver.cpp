#include "sewer3d/posegraph/solver.hpp"

#include <ceres/ceres.h>
#include <ceres/normal_prior.h>
#include <ceres/sphere_manifold.h>

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <map>
#include <unordered_map>

#include "sewer3d/core/check.hpp"
#include "sewer3d/posegraph/axis_curve_cost.hpp"
#include "sewer3d/posegraph/block_algebra.hpp"
#include "sewer3d/posegraph/certificate.hpp"
#include "sewer3d/posegraph/edge_cost.hpp"

namespace sewer3d {
namespace {

using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

/// Node ids -> dense indices, with the anchored (fixed) nodes marked.
struct Indexing {
  std::unordered_map<int, int> index_of_id;
  std::vector<int> id_of_index;
  std::vector<int> free_index;  // per node index: position among free nodes, or -1 if anchored
  int free_count = 0;
};

// Nodes without a chain of edges to an anchor (a fixed node, or the first when none is fixed):
// nothing determines their poses.
int CountUnanchoredNodes(const PoseGraph& graph, const Indexing& ix) {
  std::vector<int> parent(ix.id_of_index.size());
  for (size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  const auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const PoseEdge& e : graph.edges())
    parent[root(ix.index_of_id.at(e.from))] = root(ix.index_of_id.at(e.to));
  std::vector<bool> anchored(parent.size(), false);
  for (size_t i = 0; i < parent.size(); ++i)
    if (ix.free_index[i] < 0) anchored[root(static_cast<int>(i))] = true;
  int count = 0;
  for (size_t i = 0; i < parent.size(); ++i) count += !anchored[root(static_cast<int>(i))];
  return count;
}

Indexing MakeIndexing(const PoseGraph& graph) {
  Indexing ix;
  for (const auto& [id, pose] : graph.nodes()) {
    ix.index_of_id[id] = static_cast<int>(ix.id_of_index.size());
    ix.id_of_index.push_back(id);
  }
  ix.free_index.assign(ix.id_of_index.size(), 0);
  std::vector<int> anchors = graph.fixed_nodes();
  if (anchors.empty() && !graph.nodes().empty()) anchors.push_back(graph.nodes().begin()->first);
  for (int id : anchors) ix.free_index[ix.index_of_id.at(id)] = -1;
  for (auto& f : ix.free_index) f = f < 0 ? -1 : ix.free_count++;
  return ix;
}

/// Assembles and solves H x = B for a problem with residuals e = x_b − M x_a − c, weight W,
/// anchored nodes known. `known(i)` gives the fixed value (3 x k) of an anchored node.
template <class EdgeTerms, class Known>
std::optional<Eigen::MatrixXd> SolveLinear(const PoseGraph& graph, const Indexing& ix, int rhs_cols,
                                           EdgeTerms&& terms, Known&& known) {
  const int n = 3 * ix.free_count;
  Triplets triplets;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, rhs_cols);
  for (const PoseEdge& e : graph.edges()) {
    const int a = ix.index_of_id.at(e.from), b = ix.index_of_id.at(e.to);
    Eigen::Matrix3d m, w;
    Eigen::MatrixXd c;  // 3 x rhs_cols
    terms(e, a, m, w, c);
    const int fa = ix.free_index[a], fb = ix.free_index[b];
    // Normal equations of e = x_b − M x_a − c with weight W.
    if (fa >= 0) {
      AddBlock(triplets, 3 * fa, 3 * fa, m.transpose() * w * m);
      rhs.middleRows<3>(3 * fa) -= m.transpose() * w * c;
    }
    if (fb >= 0) {
      AddBlock(triplets, 3 * fb, 3 * fb, w);
      rhs.middleRows<3>(3 * fb) += w * c;
    }
    if (fa >= 0 && fb >= 0) {
      AddBlock(triplets, 3 * fa, 3 * fb, -m.transpose() * w);
      AddBlock(triplets, 3 * fb, 3 * fa, -w * m);
    } else if (fa >= 0) {
      rhs.middleRows<3>(3 * fa) += m.transpose() * w * known(b);
    } else if (fb >= 0) {
      rhs.middleRows<3>(3 * fb) += w * m * known(a);
    }
  }
  Eigen::SparseMatrix<double> h(n, n);
  h.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(h);
  if (ldlt.info() != Eigen::Success) return std::nullopt;
  Eigen::MatrixXd x = ldlt.solve(rhs);
  if (ldlt.info() != Eigen::Success || !x.allFinite()) return std::nullopt;
  // A disconnected graph leaves a singular H; LDLT may still "succeed" with zero pivots.
  if ((h * x - rhs).norm() > 1e-6 * std::max(1.0, rhs.norm())) return std::nullopt;
  return x;
}

}  // namespace

Matrix6d SqrtInformation(const Matrix6d& information) {
  const Eigen::LLT<Matrix6d> llt(information);
  SEWER3D_CHECK(llt.info() == Eigen::Success, "information not positive definite");
  return llt.matrixU();
}

void PoseGraphOptions::Check() const {
  SEWER3D_VALIDATE(max_iterations > 0, "max_iterations", "must be > 0, got " << max_iterations);
  SEWER3D_VALIDATE(num_threads > 0, "num_threads", "must be > 0, got " << num_threads);
  SEWER3D_VALIDATE(std::isfinite(huber_delta), "huber_delta", "must be finite");
}

bool ChordalInitialisation(PoseGraph& graph) {
  const Indexing ix = MakeIndexing(graph);
  if (ix.free_count == 0) return true;
  std::vector<Eigen::Matrix3d> rotation(ix.id_of_index.size());
  for (size_t i = 0; i < rotation.size(); ++i) {
    rotation[i] = graph.node(ix.id_of_index[i]).RotationMatrix();
  }
  // Rotations: each row r_k of every R solves the same system x_b = R̂ᵀ x_a (x = r_kᵀ), so one
  // factorisation serves three right-hand sides (the rows of the anchors' rotations).
  const auto rows = SolveLinear(
      graph, ix, 3,
      [](const PoseEdge& e, int, Eigen::Matrix3d& m, Eigen::Matrix3d& w, Eigen::MatrixXd& c) {
        m = e.a_from_b.RotationMatrix().transpose();
        w = Eigen::Matrix3d::Identity() * (e.information.bottomRightCorner<3, 3>().trace() / 3.0);
        c = Eigen::MatrixXd::Zero(3, 3);
      },
      [&](int i) -> Eigen::MatrixXd { return rotation[i].transpose(); });
  if (!rows) return false;
  for (size_t i = 0; i < rotation.size(); ++i) {
    const int f = ix.free_index[i];
    if (f >= 0) rotation[i] = ProjectToRotation(rows->middleRows<3>(3 * f).transpose());
  }
  // Positions: p_b − p_a = R_a p̂_ab, weighted by the translation information in world axes.
  const auto positions = SolveLinear(
      graph, ix, 1,
      [&](const PoseEdge& e, int a, Eigen::Matrix3d& m, Eigen::Matrix3d& w, Eigen::MatrixXd& c) {
        m = Eigen::Matrix3d::Identity();
        const Eigen::Matrix3d omega = e.information.topLeftCorner<3, 3>();
        w = rotation[a] * (0.5 * (omega + omega.transpose())) * rotation[a].transpose();
        c = rotation[a] * e.a_from_b.translation;
      },
      [&](int i) -> Eigen::MatrixXd { return graph.node(ix.id_of_index[i]).translation; });
  if (!positions) return false;
  for (size_t i = 0; i < rotation.size(); ++i) {
    const int f = ix.free_index[i];
    if (f < 0) continue;
    graph.mutable_node(ix.id_of_index[i]) =
        Rigid3d(rotation[i], Eigen::Vector3d(positions->middleRows<3>(3 * f)));
  }
  return true;
}

namespace {

struct LmResult {
  int iterations = 0;
  double seconds = 0.0;
  std::string termination;
  bool usable = false;
};

/// The axis curve's terms (axis_curve.hpp) on the poses' blocks and the curve's, a copy of its
/// points in `curve`.
void AddCentreline(const PoseGraph& graph, const Indexing& ix, std::vector<Eigen::Vector3d>& p,
                   std::vector<Eigen::Quaterniond>& q, std::vector<Eigen::Vector3d>& curve,
                   ceres::Problem& problem) {
  const std::optional<AxisCurve>& c = graph.axis_curve();
  if (!c) return;
  curve = c->points;
  for (const AxisObservation& o : graph.axis_observations()) {
    const int i = ix.index_of_id.at(o.node);
    const int k = c->Segment(o.station_mm);
    problem.AddResidualBlock(AxisCost::Create(o, c->Fraction(k, o.station_mm)), nullptr,
                             p[i].data(), q[i].coeffs().data(), curve[k].data(),
                             curve[k + 1].data());
  }
  for (size_t k = 0; k + 2 < curve.size(); ++k) {
    problem.AddResidualBlock(CurvatureCost::Create(c->curvature_sigma_mm[k], c->along_sigma_mm),
                             nullptr, curve[k].data(), curve[k + 1].data(), curve[k + 2].data());
  }
}

/// Levenberg–Marquardt on the graph's poses, in place (left unchanged if the solve diverges).
LmResult SolveLm(PoseGraph& graph, const PoseGraphOptions& options) {
  // Parameter blocks: contiguous copies of each node's position and quaternion (x y z w).
  const Indexing ix = MakeIndexing(graph);
  const size_t count = ix.id_of_index.size();
  std::vector<Eigen::Vector3d> p(count);
  std::vector<Eigen::Quaterniond> q(count);
  for (size_t i = 0; i < count; ++i) {
    const Rigid3d& pose = graph.node(ix.id_of_index[i]);
    p[i] = pose.translation;
    q[i] = pose.rotation;
  }
  std::map<int, Eigen::Matrix<double, 6, 1>> bias;
  for (const auto& [id, b] : graph.biases()) bias[id] = b.value;
  ceres::Problem problem;
  for (const PoseEdge& e : graph.edges()) {
    const int a = ix.index_of_id.at(e.from), b = ix.index_of_id.at(e.to);
    const double delta = e.huber_delta > 0.0 ? e.huber_delta : options.huber_delta;
    ceres::LossFunction* loss = delta > 0.0 ? new ceres::HuberLoss(delta) : nullptr;
    const Matrix6d sqrt_information = SqrtInformation(e.information);
    if (e.bias >= 0) {
      problem.AddResidualBlock(BiasedEdgeCost::Create(e.a_from_b, sqrt_information), loss,
                               p[a].data(), q[a].coeffs().data(), p[b].data(), q[b].coeffs().data(),
                               bias.at(e.bias).data());
    } else {
      problem.AddResidualBlock(EdgeCost::Create(e.a_from_b, sqrt_information), loss, p[a].data(),
                               q[a].coeffs().data(), p[b].data(), q[b].coeffs().data());
    }
  }
  // Each bias's prior (only those some edge uses: an unused one stays as it is).
  for (const auto& [id, b] : graph.biases()) {
    if (!problem.HasParameterBlock(bias.at(id).data())) continue;
    const Matrix6d s = SqrtInformation(b.prior_information);
    problem.AddResidualBlock(new ceres::NormalPrior(ceres::Matrix(s), ceres::Vector::Zero(6)),
                             nullptr, bias.at(id).data());
  }
  for (const BiasSum& z : graph.zero_sums()) {
    std::vector<double*> blocks;
    std::vector<Matrix6d> frames;
    for (size_t k = 0; k < z.groups.size(); ++k) {
      double* block = bias.at(z.groups[k]).data();
      if (!problem.HasParameterBlock(block)) continue;
      blocks.push_back(block);
      frames.push_back(z.frames[k]);
    }
    if (blocks.empty()) continue;
    problem.AddResidualBlock(new BiasSumCost(std::move(frames), SqrtInformation(z.information)),
                             nullptr, blocks);
  }
  Eigen::Vector3d direction = graph.world_direction();
  for (const DirectionObservation& d : graph.directions()) {
    const int i = ix.index_of_id.at(d.node);
    problem.AddResidualBlock(DirectionCost::Create(d.in_node, d.sigma_rad), nullptr,
                             q[i].coeffs().data(), direction.data());
  }
  if (!graph.directions().empty())
    problem.SetManifold(direction.data(), new ceres::SphereManifold<3>);
  std::vector<Eigen::Vector3d> curve;
  AddCentreline(graph, ix, p, q, curve, problem);
  for (size_t i = 0; i < count; ++i) {
    if (!problem.HasParameterBlock(q[i].coeffs().data())) continue;
    problem.SetManifold(q[i].coeffs().data(), new ceres::EigenQuaternionManifold);
    if (ix.free_index[i] >= 0) continue;
    if (problem.HasParameterBlock(p[i].data())) problem.SetParameterBlockConstant(p[i].data());
    problem.SetParameterBlockConstant(q[i].coeffs().data());
  }
  ceres::Solver::Options solver_options;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.num_threads = options.num_threads;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  ceres::Solver::Summary summary;
  const auto solve_start = Clock::now();
  if (problem.NumResidualBlocks() > 0) ceres::Solve(solver_options, &problem, &summary);
  LmResult result;
  result.seconds = Seconds(solve_start);

  bool finite = true;
  for (size_t i = 0; i < count; ++i)
    finite = finite && p[i].allFinite() && q[i].coeffs().allFinite();
  for (const auto& [id, b] : bias) finite = finite && b.allFinite();
  finite = finite && direction.allFinite();
  for (const Eigen::Vector3d& c : curve) finite = finite && c.allFinite();
  if (finite) {  // a diverged solve leaves the initial poses and biases in place
    for (size_t i = 0; i < count; ++i) graph.mutable_node(ix.id_of_index[i]) = Rigid3d(q[i], p[i]);
    for (const auto& [id, b] : bias) graph.mutable_biases().at(id).value = b;
    if (!graph.directions().empty()) graph.SetWorldDirection(direction);
    if (graph.axis_curve()) graph.mutable_axis_curve().points = curve;
  }
  // Ceres reports -1 steps when it did not iterate.
  result.iterations =
      std::max(0, summary.num_successful_steps) + std::max(0, summary.num_unsuccessful_steps);
  result.termination = problem.NumResidualBlocks() == 0
                           ? "no edges"
                           : ceres::TerminationTypeToString(summary.termination_type) +
                                 std::string(": ") + summary.message;
  result.usable = finite && (problem.NumResidualBlocks() == 0 || summary.IsSolutionUsable());
  return result;
}

/// The staircase from LM's result: lower bound, and its rounded solution refined by LM where
/// that ends lower.
void Certify(PoseGraph& graph, const PoseGraphOptions& options, PoseGraphReport& report) {
  const auto start = Clock::now();
  if (options.huber_delta > 0.0) {
    report.certificate_reason = "robust loss";
    return;
  }
  if (!graph.biases().empty()) {
    report.certificate_reason = "edge biases (estimated with the poses: not a pose graph)";
    return;
  }
  if (!graph.directions().empty()) {
    report.certificate_reason = "direction observations (not a pose graph)";
    return;
  }
  if (graph.axis_curve()) {
    report.certificate_reason = "a centreline (estimated with the poses: not a pose graph)";
    return;
  }
  PoseGraph rounded;
  const CertificateReport c = CertifyPoseGraph(graph, CertificateOptions(), &rounded);
  report.certificate_applicable = c.applicable;
  report.certificate_reason = c.reason;
  if (!c.applicable) return;
  report.lower_bound = c.lower_bound;
  report.relaxation_rank = c.rank;
  report.relaxation_solved = c.relaxation_solved;
  report.dominated_edges = c.dominated_edges;
  report.dominated_relaxation = c.dominated_relaxation;
  const LmResult refined = SolveLm(rounded, options);
  const double refined_cost = GraphCost(rounded);
  if (refined.usable && refined_cost < report.final_cost) {
    graph = std::move(rounded);
    report.final_cost = refined_cost;
    report.iterations += refined.iterations;
    report.certificate_improved = true;
  }
  report.certificate_seconds = Seconds(start);
}

}  // namespace

PoseGraphReport OptimisePoseGraph(PoseGraph& graph, const PoseGraphOptions& options) {
  options.Check();
  PoseGraphReport report;
  report.nodes = static_cast<int>(graph.nodes().size());
  report.edges = static_cast<int>(graph.edges().size());
  report.given_cost = GraphCost(graph);
  report.init_used = "given";

  const auto init_start = Clock::now();
  if (options.init != PoseGraphInit::kGiven) {
    PoseGraph chordal = graph;
    if (ChordalInitialisation(chordal)) {
      const double chordal_cost = GraphCost(chordal);
      if (options.init == PoseGraphInit::kChordal || chordal_cost < report.given_cost) {
        graph = std::move(chordal);
        report.init_used = "chordal";
      }
    } else if (options.init == PoseGraphInit::kChordal) {
      report.termination = "chordal initialisation failed: graph not connected to its anchor";
      report.init_seconds = Seconds(init_start);
      report.initial_cost = report.final_cost = report.given_cost;
      return report;
    }
  }
  report.init_seconds = Seconds(init_start);
  report.initial_cost = GraphCost(graph);

  const LmResult lm = SolveLm(graph, options);
  report.solve_seconds = lm.seconds;
  report.iterations = lm.iterations;
  report.termination = lm.termination;
  report.usable = lm.usable;
  report.unanchored_nodes = CountUnanchoredNodes(graph, MakeIndexing(graph));
  report.final_cost = GraphCost(graph);
  if (options.certify && report.usable) Certify(graph, options, report);
  return report;
}

}  // namespace sewer3d
