#pragma once
/// \file
/// The pose-graph cost as a quadratic form in the rotation matrices, positions eliminated.
///
/// Where every edge's translation information is isotropic (τ I, no cross terms) the cost of
/// solver.hpp is exactly quadratic in the rotations: with E = R̂_ab R_bᵀ R_a and v = vec(q_E),
/// v vᵀ = ¼ (E + Eᵀ) − ¼ (tr E − 1) I, so the rotation term ½ (2v)ᵀ Ω_r (2v) equals
/// tr(M E) + ½ tr Ω_r with M = Ω_r − ½ tr Ω_r I, bilinear in R_a and R_b, and the translation
/// term ½ τ ‖p_b − p_a − R_a p̂_ab‖² is quadratic in (p, R). Minimising over the positions
/// (a Schur complement; one node holds the gauge) leaves
///
///     F(R) = tr(Xᵀ Q X) + c,   X = [R_1 ... R_n]ᵀ  (3n × 3, block i = R_iᵀ),
///
/// an SE-Sync-type problem (Rosen et al., IJRR 2019) with matrix-weighted rotation terms. The
/// same form accepts X of any width r (blocks 3 × r with orthonormal rows): the Stiefel lift of
/// the Riemannian staircase (certificate.hpp).

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sewer3d/posegraph/pose_graph.hpp"

namespace sewer3d {

/// An edge's rotation term is a squared norm, ½ ‖(R_a R̂ − R_b) W‖²_F with W Wᵀ = R̂ᵀ(½ tr Ω_r I −
/// Ω_r)R̂, and so stays non-negative in the Stiefel lift, exactly when ½ tr Ω_r I − Ω_r ⪰ 0: when
/// the largest eigenvalue of Ω_r is at most the sum of the other two. Otherwise the lifted cost can
/// go negative and the relaxation loses its tightness, even without noise. Returns Ω_r with its
/// largest eigenvalue lowered to the sum of the other two where needed: the largest such matrix
/// below Ω_r along its eigenvectors, so its cost bounds Ω_r's from below.
Eigen::Matrix3d DominatedRotationInformation(const Eigen::Matrix3d& information);

/// A block-diagonal information diag(τI, Ω_r') ⪯ Ω whose cost is quadratic in the rotations
/// and stays a sum of squares in the lift: τ = tr Ω_t / 3 and Ω_r' = Ω_r where Ω already has
/// isotropic translation information and no coupling; otherwise τ from λ_min(Ω_t) and Ω_r'
/// from the Schur complement; then DominatedRotationInformation. Its cost is below Ω's for
/// every residual.
Matrix6d DominatedInformation(const Matrix6d& information);

enum class RotationInformation {
  kExact,      ///< the graph's Ω: F is the graph's cost (isotropic translation information only)
  kDominated,  ///< DominatedInformation(Ω): F is a lower bound of the graph's cost, any Ω
};

class RotationForm {
 public:
  /// Builds the form; nullopt with `why` set when the graph does not qualify: robust losses,
  /// no edges, a graph not connected, and for kExact anisotropic translation information or
  /// translation–rotation cross terms (relative size > 1e-6).
  static std::optional<RotationForm> Build(
      const PoseGraph& graph, std::string* why,
      RotationInformation rotation_information = RotationInformation::kExact);

  /// c = Σ ½ tr Ω_r: the cost's scale (every rotation residual at 90° costs about this).
  double Constant() const { return constant_; }

  /// Edges whose information DominatedInformation lowers (lowered in kDominated).
  int DominatedEdges() const { return dominated_edges_; }

  int NodeCount() const { return static_cast<int>(ids_.size()); }
  /// Node ids in the order of X's blocks.
  const std::vector<int>& Ids() const { return ids_; }

  /// Q X for X (3n × r).
  Eigen::MatrixXd Apply(const Eigen::MatrixXd& x) const;
  /// ½ Σ rᵀΩr at the rotations X (3n × 3) and the best positions for them: tr(XᵀQX) + c.
  double Cost(const Eigen::MatrixXd& x) const;
  /// tr(XᵀQX) + c given Q X already computed.
  double Cost(const Eigen::MatrixXd& x, const Eigen::MatrixXd& qx) const;
  /// The positions minimising the cost for the rotations X (n × r, one row per node), with
  /// node 0 of Ids() at the origin.
  Eigen::MatrixXd Positions(const Eigen::MatrixXd& x) const;
  /// Whether Q − Diag(blocks) + shift·I is positive definite (blocks: one symmetric 3 × 3 per
  /// node), decided by a sparse Cholesky factorisation of the matrix before the positions are
  /// eliminated, [[L, B], [Bᵀ, C − Diag(blocks) + shift·I]]: with L ≻ 0 it is positive definite
  /// exactly when its Schur complement is.
  bool IsPositiveDefinite(const std::vector<Eigen::Matrix3d>& blocks, double shift) const;

  /// The smallest η in from·4^k ≤ to for which Q − Diag(blocks) + ηI is positive definite, by
  /// the same factorisation (one symbolic analysis for all η); nullopt if none or from ≤ 0.
  std::optional<double> SmallestPositiveDefiniteShift(const std::vector<Eigen::Matrix3d>& blocks,
                                                      double from, double to) const;

  /// A sparse positive-definite matrix for preconditioning: the rotation terms of Q made
  /// diagonally dominant (½‖M‖ I per edge end), plus a 1e-6 relative regularisation. The
  /// translation terms are left out: before position elimination they overstate Q by far in
  /// most directions, and with them CG needed ~30× more iterations on anisotropic graphs.
  const Eigen::SparseMatrix<double>& Approximation() const { return approximation_; }

 private:
  std::vector<int> ids_;
  Eigen::SparseMatrix<double> direct_;     // 3n × 3n: rotation terms + translation C block
  Eigen::SparseMatrix<double> coupling_;   // (n−1) × 3n: position–rotation block B
  Eigen::SparseMatrix<double> laplacian_;  // (n−1) × (n−1): positions, node 0 grounded
  std::shared_ptr<const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> laplacian_factor_;
  Eigen::SparseMatrix<double> approximation_;
  double constant_ = 0.0;
  int dominated_edges_ = 0;
};

}  // namespace sewer3d
