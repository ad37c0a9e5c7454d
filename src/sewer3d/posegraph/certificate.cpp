#include "sewer3d/posegraph/certificate.hpp"

#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <limits>

#include "sewer3d/core/check.hpp"
#include "sewer3d/posegraph/block_algebra.hpp"
#include "sewer3d/posegraph/certificate_eigen.hpp"
#include "sewer3d/posegraph/lifted_cost.hpp"
#include "sewer3d/posegraph/rotation_form.hpp"

namespace sewer3d {
namespace {

using Eigen::MatrixXd;
using lifted::CertificateProduct;
using lifted::Eigenpair;
using lifted::Inner;
using lifted::LargestEigenvalueMagnitude;
using lifted::MinimumEigenpair;
using lifted::MultiplierBlocks;
using lifted::Point;
using lifted::Project;
using lifted::Retract;

/// Eigensolver runs per certificate check before it gives up.
constexpr int kEigenAttempts = 3;

/// The exact relaxation counts as tight when its rounded solution is this close to its bound.
constexpr double kTightGap = 1e-4;

class TrustRegion {
 public:
  TrustRegion(const RotationForm& form, const CertificateOptions& options)
      : form_(form), options_(options), preconditioner_(form.Approximation()) {}

  /// Minimises from `point` to a first-order critical point; returns iterations used.
  int Minimise(Point& point) {
    double radius = -1.0;
    int iteration = 0;
    for (; iteration < options_.max_iterations; ++iteration) {
      const double gradient_norm = point.gradient.norm();
      if (gradient_norm <= options_.relative_gradient_tolerance * point.qx.norm()) break;
      if (radius < 0.0) radius = std::min(1.0, gradient_norm);
      bool on_boundary = false;
      MatrixXd hessian_step;
      const MatrixXd step = TruncatedCg(point, radius, hessian_step, on_boundary);
      const double model_decrease =
          -(Inner(point.gradient, step) + 0.5 * Inner(step, hessian_step));
      Point candidate(form_, Retract(point.x, step));
      // ρ regularised against round-off near convergence (as Manopt does).
      const double round_off =
          1e3 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(point.cost));
      const double rho = (point.cost - candidate.cost + round_off) / (model_decrease + round_off);
      if (rho < 0.25) {
        radius *= 0.25;
      } else if (rho > 0.75 && on_boundary) {
        radius *= 2.0;
      }
      if (rho > 0.1) {
        point = std::move(candidate);
      } else if (radius < 1e-10) {
        break;
      }
    }
    return iteration;
  }

 private:
  MatrixXd Hessian(const Point& p, const MatrixXd& v) const { return p.Hessian(form_, v); }

  MatrixXd Precondition(const Point& p, const MatrixXd& v) const {
    return Project(p.x, preconditioner_.solve(v));
  }

  /// Steihaug–Toint truncated CG on the model ⟨g, η⟩ + ½⟨η, Hη⟩ within the trust region
  /// measured in the preconditioner's norm (Absil, Baker, Gallivan 2007).
  MatrixXd TruncatedCg(const Point& p, double radius, MatrixXd& h_eta, bool& on_boundary) const {
    MatrixXd eta = MatrixXd::Zero(p.x.rows(), p.x.cols());
    h_eta = eta;
    MatrixXd r = p.gradient;
    MatrixXd z = Precondition(p, r);
    double z_r = Inner(z, r);
    MatrixXd delta = -z;
    double e_pe = 0.0, e_pd = 0.0, d_pd = z_r;
    const double r0 = r.norm();
    for (int j = 0; j < options_.max_cg_iterations; ++j) {
      const MatrixXd h_delta = Hessian(p, delta);
      const double d_hd = Inner(delta, h_delta);
      const double alpha = z_r / d_hd;
      const double e_pe_next = e_pe + 2.0 * alpha * e_pd + alpha * alpha * d_pd;
      if (d_hd <= 0.0 || e_pe_next >= radius * radius) {
        const double tau =
            (-e_pd + std::sqrt(e_pd * e_pd + d_pd * (radius * radius - e_pe))) / d_pd;
        eta += tau * delta;
        h_eta += tau * h_delta;
        on_boundary = true;
        return eta;
      }
      e_pe = e_pe_next;
      eta += alpha * delta;
      h_eta += alpha * h_delta;
      r = Project(p.x, r + alpha * h_delta);
      const double r_norm = r.norm();
      if (r_norm <= r0 * std::min(r0, 0.1)) break;  // κ = 0.1, θ = 1: superlinear
      z = Precondition(p, r);
      const double z_r_next = Inner(z, r);
      const double beta = z_r_next / z_r;
      z_r = z_r_next;
      delta = -z + beta * delta;
      e_pd = beta * (e_pd + alpha * d_pd);
      d_pd = z_r + beta * beta * d_pd;
    }
    return eta;
  }

  const RotationForm& form_;
  const CertificateOptions& options_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> preconditioner_;
};

/// Rounds X (3n × r) to rotations: the top-3 right singular subspace, the sign that gives
/// most blocks a positive determinant, each block projected onto SO(3). Returns 3n × 3.
MatrixXd Round(const MatrixXd& x) {
  const Eigen::SelfAdjointEigenSolver<MatrixXd> es(x.transpose() * x);
  MatrixXd basis = es.eigenvectors().rightCols(3);  // r × 3, largest three
  MatrixXd rotations = x * basis;
  int positive = 0;
  for (Eigen::Index i = 0; i < x.rows(); i += 3)
    positive += rotations.middleRows<3>(i).determinant() > 0.0;
  if (2 * positive < x.rows() / 3) rotations.col(2) *= -1.0;
  for (Eigen::Index i = 0; i < x.rows(); i += 3) {
    rotations.middleRows<3>(i) = ProjectToRotation(rotations.middleRows<3>(i));
  }
  return rotations;
}

/// Escapes the saddle at rank r along the eigenvector v of λ_min < 0: X⁺ = R([X 0] + α[0 v]),
/// halving α until the cost drops.
std::optional<MatrixXd> Escape(const RotationForm& form, const Point& point,
                               const Eigen::VectorXd& v) {
  MatrixXd lifted = MatrixXd::Zero(point.x.rows(), point.x.cols() + 1);
  lifted.leftCols(point.x.cols()) = point.x;
  MatrixXd direction = MatrixXd::Zero(lifted.rows(), lifted.cols());
  direction.rightCols(1) = v.normalized();
  for (double alpha = std::sqrt(static_cast<double>(form.NodeCount())); alpha > 1e-8;
       alpha *= 0.5) {
    MatrixXd candidate = Retract(lifted, alpha * direction);
    if (form.Cost(candidate) < point.cost) return candidate;
  }
  return std::nullopt;
}

/// The graph with the rounded rotations (3n × 3) and their best positions, in the input's
/// gauge: the anchor (first fixed node, else the first node) keeps its pose.
PoseGraph RoundedGraph(const PoseGraph& graph, const RotationForm& form,
                       const MatrixXd& rotations) {
  const MatrixXd positions = form.Positions(rotations);
  PoseGraph out = graph;
  for (int i = 0; i < form.NodeCount(); ++i) {
    const Eigen::Matrix3d r = rotations.middleRows<3>(3 * i).transpose();
    out.mutable_node(form.Ids()[i]) =
        Rigid3d(Eigen::Quaterniond(r), Eigen::Vector3d(positions.row(i).transpose()));
  }
  const int anchor = graph.fixed_nodes().empty() ? form.Ids()[0] : graph.fixed_nodes()[0];
  const Rigid3d world_from_rounded = graph.node(anchor) * out.node(anchor).Inverse();
  for (const auto& [id, pose] : graph.nodes())
    out.mutable_node(id) = world_from_rounded * out.node(id);
  return out;
}

}  // namespace

void CertificateOptions::Check() const {
  SEWER3D_VALIDATE(max_rank >= 3, "max_rank", "must be >= 3, got " << max_rank);
  SEWER3D_VALIDATE(max_iterations > 0, "max_iterations", "must be > 0, got " << max_iterations);
  SEWER3D_VALIDATE(max_cg_iterations > 0, "max_cg_iterations",
                   "must be > 0, got " << max_cg_iterations);
  ValidatePositive("relative_gradient_tolerance", relative_gradient_tolerance);
  ValidatePositive("relative_eigenvalue_tolerance", relative_eigenvalue_tolerance);
}

namespace {

/// One staircase on `relaxed` from rotations `x` (3n × 3); fills the relaxation fields of
/// `report` and returns the rounded rotations.
MatrixXd Staircase(const RotationForm& relaxed, const MatrixXd& x,
                   const CertificateOptions& options, CertificateReport& report) {
  Point point(relaxed, x);
  TrustRegion trust_region(relaxed, options);
  const double dimension = static_cast<double>(x.rows());
  report.lower_bound = -std::numeric_limits<double>::infinity();
  for (report.rank = 3;; ++report.rank) {
    report.iterations += trust_region.Minimise(point);
    report.relaxation_cost = point.cost;
    // S ⪰ 0 is decided by a sparse factorisation of S + ηI for growing η; only when that
    // fails is the eigenvector of λ_min needed, to climb along. Lanczos can miss the lowest
    // eigenvalue; the factorisation cannot: restart from other vectors until both agree.
    const double largest = LargestEigenvalueMagnitude(relaxed, point.lambda);
    const double tolerance = options.relative_eigenvalue_tolerance * largest;
    std::optional<double> eta =
        relaxed.SmallestPositiveDefiniteShift(point.lambda, 1e-14 * largest, tolerance);
    Eigenpair lowest;
    lowest.converged = true;
    for (int attempt = 0; attempt < kEigenAttempts && !eta; ++attempt) {
      lowest = MinimumEigenpair(relaxed, point.lambda, attempt, largest);
      report.eigen_iterations += lowest.restarts;
      if (lowest.converged && lowest.value < -tolerance) break;  // descend along it
    }
    if (eta) {
      report.relaxation_solved = true;
      report.min_eigenvalue = -*eta;                       // verified: λ_min(S) > −η
      report.lower_bound = point.cost - dimension * *eta;  // weak duality with Λ − ηI
      break;
    }
    report.min_eigenvalue = lowest.value;
    std::optional<MatrixXd> escaped;
    const bool negative = lowest.converged && lowest.value < -tolerance;
    if (negative && report.rank < options.max_rank) escaped = Escape(relaxed, point, lowest.vector);
    if (!escaped) {
      report.reason = !lowest.converged ? "the certificate's eigenvalue did not converge"
                      : !negative ? "the eigensolver found no eigenvalue below the factorisation's"
                      : report.rank >= options.max_rank
                          ? "the staircase reached its maximum rank"
                          : "no descent along the certificate's eigenvector";
      // A valid but looser bound: weak duality with the shift the factorisation accepts.
      if (const auto loose =
              relaxed.SmallestPositiveDefiniteShift(point.lambda, tolerance, 4.0 * largest)) {
        report.lower_bound = point.cost - dimension * *loose;
      }
      break;
    }
    point = Point(relaxed, std::move(*escaped));
  }
  return Round(point.x);
}

}  // namespace

CertificateReport CertifyPoseGraph(const PoseGraph& graph, const CertificateOptions& options,
                                   PoseGraph* rounded) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  CertificateReport report;
  if (graph.fixed_nodes().size() > 1) {
    report.reason = "more than one node is fixed";
    return report;
  }
  // The exact form where the cost is quadratic in the rotations; the dominated one (a lower
  // cost, so a valid bound) where it is loose or the translation information is anisotropic.
  const std::optional<RotationForm> exact = RotationForm::Build(graph, nullptr);
  std::optional<RotationForm> dominated;
  if (!exact) {
    dominated = RotationForm::Build(graph, &report.reason, RotationInformation::kDominated);
    if (!dominated) return report;  // robust loss, disconnected, no edges
  }
  const RotationForm& any = exact ? *exact : *dominated;
  report.applicable = true;
  report.dominated_edges = any.DominatedEdges();
  const int n = any.NodeCount();
  MatrixXd x(3 * n, 3);
  for (int i = 0; i < n; ++i)
    x.middleRows<3>(3 * i) = graph.node(any.Ids()[i]).RotationMatrix().transpose();
  // The graph's cost at rotations with the form's best positions for them.
  auto cost = [&](const MatrixXd& r) {
    return exact ? exact->Cost(r) : GraphCost(RoundedGraph(graph, any, r));
  };
  report.start_cost = cost(x);
  report.lower_bound = -std::numeric_limits<double>::infinity();
  report.rounded_cost = std::numeric_limits<double>::infinity();

  MatrixXd rotations = x;
  if (exact) {
    rotations = Staircase(*exact, x, options, report);
    report.rounded_cost = exact->Cost(rotations);
  }
  const double gap = report.rounded_cost - report.lower_bound;
  const bool loose = !exact || !(gap <= kTightGap * std::max(std::abs(report.rounded_cost),
                                                             1e-6 * any.Constant()));
  if (loose && !dominated && any.DominatedEdges() > 0) {
    dominated = RotationForm::Build(graph, nullptr, RotationInformation::kDominated);
  }
  if (dominated && loose) {
    CertificateReport second = report;
    second.reason.clear();
    second.relaxation_solved = false;
    const MatrixXd candidate = Staircase(*dominated, x, options, second);
    second.rounded_cost = cost(candidate);
    const double exact_rounded_cost = report.rounded_cost;
    if (second.lower_bound > report.lower_bound) {
      report = second;
      report.dominated_relaxation = true;
    }
    report.iterations = second.iterations;
    report.eigen_iterations = second.eigen_iterations;
    report.rounded_cost = std::min(exact_rounded_cost, second.rounded_cost);
    if (second.rounded_cost < exact_rounded_cost) rotations = candidate;
  }
  if (rounded) *rounded = RoundedGraph(graph, any, rotations);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace sewer3d
