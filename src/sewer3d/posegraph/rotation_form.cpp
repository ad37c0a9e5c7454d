#include "sewer3d/posegraph/rotation_form.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <string>
#include <unordered_map>

#include "sewer3d/posegraph/block_algebra.hpp"

namespace sewer3d {
namespace {

/// Why the edge's cost is not exactly quadratic in the rotations, or empty.
std::string Disqualification(const Matrix6d& information) {
  const Eigen::Matrix3d omega_t = information.topLeftCorner<3, 3>();
  const double tau = omega_t.trace() / 3.0;
  const double scale = std::max(tau, information.bottomRightCorner<3, 3>().cwiseAbs().maxCoeff());
  if ((omega_t - tau * Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 * tau) {
    return "has anisotropic translation information";
  }
  if (information.topRightCorner<3, 3>().cwiseAbs().maxCoeff() > 1e-6 * scale) {
    return "couples translation and rotation information";
  }
  return {};
}

}  // namespace

Eigen::Matrix3d DominatedRotationInformation(const Eigen::Matrix3d& information) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 *
                                                          (information + information.transpose()));
  Eigen::Vector3d lambda = es.eigenvalues();  // ascending
  if (lambda(2) <= lambda(0) + lambda(1)) return information;
  lambda(2) = lambda(0) + lambda(1);
  return es.eigenvectors() * lambda.asDiagonal() * es.eigenvectors().transpose();
}

Matrix6d DominatedInformation(const Matrix6d& information) {
  const Matrix6d omega = 0.5 * (information + information.transpose());
  Matrix6d out = Matrix6d::Zero();
  Eigen::Matrix3d omega_r = omega.bottomRightCorner<3, 3>();
  if (Disqualification(omega).empty()) {
    out.topLeftCorner<3, 3>() =
        omega.topLeftCorner<3, 3>().trace() / 3.0 * Eigen::Matrix3d::Identity();
  } else {
    // diag(τI, Ω_r − Cᵀ(Ω_t − τI)⁻¹C) ⪯ Ω for τ < λ_min(Ω_t) (Schur complement). τ = λ_min
    // without coupling C; with it, halved from λ_min until the rotation block stays positive
    // definite (it is at τ = 0, since Ω ≻ 0).
    const Eigen::Matrix3d omega_t = omega.topLeftCorner<3, 3>();
    const Eigen::Matrix3d coupling = omega.topRightCorner<3, 3>();
    double tau = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(omega_t, Eigen::EigenvaluesOnly)
                     .eigenvalues()(0);
    if (coupling.cwiseAbs().maxCoeff() > 0.0) {
      for (int halving = 0; halving < 60; ++halving) {
        tau *= 0.5;
        const Eigen::Matrix3d schur =
            omega_r - coupling.transpose() *
                          (omega_t - tau * Eigen::Matrix3d::Identity()).inverse() * coupling;
        if (Eigen::LLT<Eigen::Matrix3d>(schur).info() == Eigen::Success) {
          omega_r = schur;
          break;
        }
        if (halving == 59)
          tau = 0.0, omega_r = omega_r - coupling.transpose() * omega_t.inverse() * coupling;
      }
    }
    out.topLeftCorner<3, 3>() = tau * Eigen::Matrix3d::Identity();
  }
  out.bottomRightCorner<3, 3>() = DominatedRotationInformation(omega_r);
  return out;
}

std::optional<RotationForm> RotationForm::Build(const PoseGraph& graph, std::string* why,
                                                RotationInformation rotation_information) {
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return std::nullopt;
  };
  if (graph.edges().empty()) return fail("the graph has no edges");
  RotationForm form;
  std::unordered_map<int, int> index;
  for (const auto& [id, pose] : graph.nodes()) {
    index[id] = static_cast<int>(form.ids_.size());
    form.ids_.push_back(id);
  }
  const int n = form.NodeCount();
  Triplets direct, coupling, laplacian, dominance;
  for (const PoseEdge& e : graph.edges()) {
    const std::string edge = "edge " + std::to_string(e.from) + " -> " + std::to_string(e.to) + " ";
    if (e.huber_delta > 0.0) return fail(edge + "has a robust loss");
    const std::string reason = Disqualification(e.information);
    if (!reason.empty() && rotation_information == RotationInformation::kExact)
      return fail(edge + reason);
    const int a = index.at(e.from), b = index.at(e.to);
    const Matrix6d dominated = DominatedInformation(e.information);
    const bool lowered = !reason.empty() || dominated.bottomRightCorner<3, 3>() !=
                                                e.information.bottomRightCorner<3, 3>();
    form.dominated_edges_ += lowered;
    const Matrix6d& information =
        rotation_information == RotationInformation::kDominated ? dominated : e.information;
    const Eigen::Matrix3d omega_r = information.bottomRightCorner<3, 3>();
    const Eigen::Matrix3d m =
        0.5 * (omega_r + omega_r.transpose()) - 0.5 * omega_r.trace() * Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d rotation_ab = e.a_from_b.RotationMatrix();
    // tr(M E) = tr(R_a (½ M R̂) R_bᵀ) + tr(R_b (½ R̂ᵀ M) R_aᵀ): blocks (a, b) and (b, a).
    AddBlock(direct, 3 * a, 3 * b, 0.5 * m * rotation_ab);
    AddBlock(direct, 3 * b, 3 * a, 0.5 * rotation_ab.transpose() * m);
    AddBlock(dominance, 3 * a, 3 * b, 0.5 * m * rotation_ab);
    AddBlock(dominance, 3 * b, 3 * a, 0.5 * rotation_ab.transpose() * m);
    form.constant_ += 0.5 * omega_r.trace();
    // ½ τ ‖p_b − p_a − R_a p̂‖², with R_a p̂ = X_aᵀ p̂: the C, B and Laplacian blocks.
    const double half_tau = 0.5 * information.topLeftCorner<3, 3>().trace() / 3.0;
    const Eigen::Vector3d t = e.a_from_b.translation;
    AddBlock(direct, 3 * a, 3 * a, half_tau * t * t.transpose());
    for (int k = 0; k < 3; ++k) {
      if (b > 0) coupling.emplace_back(b - 1, 3 * a + k, -half_tau * t(k));
      if (a > 0) coupling.emplace_back(a - 1, 3 * a + k, half_tau * t(k));
    }
    if (a > 0) laplacian.emplace_back(a - 1, a - 1, half_tau);
    if (b > 0) laplacian.emplace_back(b - 1, b - 1, half_tau);
    if (a > 0 && b > 0) {
      laplacian.emplace_back(a - 1, b - 1, -half_tau);
      laplacian.emplace_back(b - 1, a - 1, -half_tau);
    }
    // Diagonal blocks ½‖M‖ I make this edge's 6 × 6 rotation block positive semidefinite.
    const double norm_m = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m, Eigen::EigenvaluesOnly)
                              .eigenvalues()
                              .cwiseAbs()
                              .maxCoeff();
    AddBlock(dominance, 3 * a, 3 * a, 0.5 * norm_m * Eigen::Matrix3d::Identity());
    AddBlock(dominance, 3 * b, 3 * b, 0.5 * norm_m * Eigen::Matrix3d::Identity());
  }
  form.direct_.resize(3 * n, 3 * n);
  form.direct_.setFromTriplets(direct.begin(), direct.end());
  form.coupling_.resize(n - 1, 3 * n);
  form.coupling_.setFromTriplets(coupling.begin(), coupling.end());
  form.laplacian_.resize(n - 1, n - 1);
  form.laplacian_.setFromTriplets(laplacian.begin(), laplacian.end());
  if (n > 1) {
    auto factor =
        std::make_shared<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(form.laplacian_);
    // A disconnected graph leaves a singular Laplacian: a (near-)zero pivot.
    const double max_diagonal = form.laplacian_.diagonal().maxCoeff();
    if (factor->info() != Eigen::Success ||
        !(factor->vectorD().minCoeff() > 1e-12 * max_diagonal)) {
      return fail("the graph is not connected");
    }
    form.laplacian_factor_ = std::move(factor);
  }
  form.approximation_.resize(3 * n, 3 * n);
  form.approximation_.setFromTriplets(dominance.begin(), dominance.end());
  const double regularisation = 1e-6 * form.approximation_.diagonal().maxCoeff();
  for (int i = 0; i < 3 * n; ++i) form.approximation_.coeffRef(i, i) += regularisation;
  return form;
}

Eigen::MatrixXd RotationForm::Apply(const Eigen::MatrixXd& x) const {
  Eigen::MatrixXd qx = direct_ * x;
  if (laplacian_factor_) qx -= coupling_.transpose() * laplacian_factor_->solve(coupling_ * x);
  return qx;
}

double RotationForm::Cost(const Eigen::MatrixXd& x, const Eigen::MatrixXd& qx) const {
  return x.cwiseProduct(qx).sum() + constant_;
}

double RotationForm::Cost(const Eigen::MatrixXd& x) const { return Cost(x, Apply(x)); }

std::optional<double> RotationForm::SmallestPositiveDefiniteShift(
    const std::vector<Eigen::Matrix3d>& blocks, double from, double to) const {
  if (!(from > 0.0)) return std::nullopt;
  const int n = NodeCount(), m = n - 1;  // m grounded positions, then 3n rotation coordinates
  Triplets t;
  t.reserve(laplacian_.nonZeros() + 2 * coupling_.nonZeros() + direct_.nonZeros() + 9 * n);
  auto append = [&t](const Eigen::SparseMatrix<double>& matrix, int row0, int col0,
                     bool transpose) {
    for (int k = 0; k < matrix.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(matrix, k); it; ++it) {
        const int r = static_cast<int>(it.row()), c = static_cast<int>(it.col());
        if (transpose)
          t.emplace_back(row0 + c, col0 + r, it.value());
        else
          t.emplace_back(row0 + r, col0 + c, it.value());
      }
    }
  };
  append(laplacian_, 0, 0, false);
  append(coupling_, 0, m, false);
  append(coupling_, m, 0, true);
  append(direct_, m, m, false);
  for (int i = 0; i < n; ++i) AddBlock(t, m + 3 * i, m + 3 * i, -blocks[i]);  // diagonal present
  Eigen::SparseMatrix<double> unshifted(m + 3 * n, m + 3 * n);
  unshifted.setFromTriplets(t.begin(), t.end());
  // One symbolic analysis; each η only refactors the numbers.
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt;
  llt.analyzePattern(unshifted);
  for (double eta = from; eta <= to; eta *= 4.0) {
    Eigen::SparseMatrix<double> shifted = unshifted;
    for (int i = m; i < m + 3 * n; ++i) shifted.coeffRef(i, i) += eta;
    llt.factorize(shifted);
    if (llt.info() == Eigen::Success) return eta;
  }
  return std::nullopt;
}

bool RotationForm::IsPositiveDefinite(const std::vector<Eigen::Matrix3d>& blocks,
                                      double shift) const {
  return SmallestPositiveDefiniteShift(blocks, shift, shift).has_value();
}

Eigen::MatrixXd RotationForm::Positions(const Eigen::MatrixXd& x) const {
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(NodeCount(), x.cols());
  if (laplacian_factor_) p.bottomRows(NodeCount() - 1) = -laplacian_factor_->solve(coupling_ * x);
  return p;
}

}  // namespace sewer3d
