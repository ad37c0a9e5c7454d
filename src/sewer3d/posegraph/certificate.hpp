#pragma once
/// \file
/// Certifiable pose-graph optimisation: the Riemannian staircase of SE-Sync (Rosen, Carlone,
/// Bandeira, Leonard, IJRR 2019) on the rotation form of rotation_form.hpp.
///
/// The rotations are lifted to X (3n × r, block i a 3 × r matrix with orthonormal rows, r ≥ 3)
/// and tr(XᵀQX) is minimised by a Riemannian trust region with truncated conjugate gradients.
/// At a critical point the Lagrange multipliers Λ_i = sym((QX)_i X_iᵀ) give the certificate
/// matrix S = Q − Diag(Λ). Weak duality, for any X: if S + ηI ⪰ 0, no poses cost less than
/// tr(XᵀQX) + c − 3nη. Positive definiteness of S + ηI is decided by a sparse Cholesky
/// factorisation (RotationForm::IsPositiveDefinite), not by an eigensolver that could miss the
/// lowest eigenvalue. If it holds for η within the tolerance, X Xᵀ solves the semidefinite
/// relaxation; otherwise the eigenvector of λ_min (Lanczos) is a descent direction at rank
/// r + 1, and the staircase climbs. The solution of the relaxation is rounded
/// to SO(3)ⁿ (top-3 singular subspace, blockwise projection) and its positions solved for.
///
/// Edges whose rotation information is strongly anisotropic (DominatedRotationInformation)
/// make the lifted cost indefinite and the relaxation loose, and anisotropic translation
/// information makes the cost non-quadratic; when the rounded solution is far from the bound,
/// or there is no exact form, a staircase relaxes the graph with its informations lowered
/// (DominatedInformation), whose cost is below the graph's everywhere, and the better bound and
/// solution are kept.

#include <string>

#include "sewer3d/posegraph/pose_graph.hpp"

namespace sewer3d {

struct CertificateOptions {
  int max_rank = 8;
  /// Trust-region iterations per rank.
  int max_iterations = 500;
  /// Inner conjugate-gradient iterations per trust-region step.
  int max_cg_iterations = 2000;
  /// Stop a rank when the Riemannian gradient norm is below this fraction of ‖Q X‖.
  double relative_gradient_tolerance = 1e-8;
  /// The relaxation counts as solved when S + ηI ≻ 0 for some η ≤ tolerance · |λ|_max(S).
  double relative_eigenvalue_tolerance = 1e-7;
  void Check() const;
};

struct CertificateReport {
  bool applicable = false;
  std::string reason;            ///< why not applicable, or why the check failed
  double start_cost = 0.0;       ///< ½ Σ rᵀΩr at the given rotations and their best positions
  double relaxation_cost = 0.0;  ///< tr(XᵀQX) + c at the last critical point
  /// λ_min(S) there: −η, the verified shift, when solved; else the eigensolver's estimate.
  double min_eigenvalue = 0.0;
  /// relaxation_cost − 3n·η with S + ηI ≻ 0 verified: no poses of the graph cost less;
  /// −∞ when no such η up to 4 |λ|_max was found.
  double lower_bound = 0.0;
  double rounded_cost = 0.0;          ///< cost of the rounded rotations with their best positions
  bool relaxation_solved = false;     ///< S ⪰ 0 within the tolerance at the final rank
  int rank = 3;                       ///< rank of the last critical point
  int dominated_edges = 0;            ///< edges whose information DominatedInformation lowers
  bool dominated_relaxation = false;  ///< the bound comes from the dominated-information relaxation
  int iterations = 0;                 ///< trust-region iterations over all ranks
  int eigen_iterations = 0;           ///< Lanczos restarts over all certificate checks
  double seconds = 0.0;
};

/// Runs the staircase from the graph's own rotations. When `rounded` is given it receives the
/// graph with the rounded rotations and their best positions, in the gauge of the graph's first
/// node (first fixed node if any). Not applicable (report.reason) with robust losses, a graph
/// not connected, or more than one node fixed.
CertificateReport CertifyPoseGraph(const PoseGraph& graph, const CertificateOptions& options,
                                   PoseGraph* rounded = nullptr);

}  // namespace sewer3d
