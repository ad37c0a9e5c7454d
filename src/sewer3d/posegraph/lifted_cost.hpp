#pragma once
/// \file
/// The lifted rotation objective f(X) = tr(XᵀQX) + c of rotation_form.hpp on the product of
/// Stiefel manifolds {X ∈ R^(3n×r) : X_i X_iᵀ = I₃ for every 3 × r block X_i} (SE-Sync's
/// Burer–Monteiro factorisation): tangent projection, retraction, Riemannian gradient and
/// Hessian, and the certificate matrix S = Q − Diag(Λ).

#include <Eigen/Core>
#include <vector>

#include "sewer3d/posegraph/rotation_form.hpp"

namespace sewer3d::lifted {

/// Λ_i blocks (3 × 3, symmetric), one per node.
using MultiplierBlocks = std::vector<Eigen::Matrix3d>;

/// Tangent projection at X: V_i − sym(V_i X_iᵀ) X_i.
Eigen::MatrixXd Project(const Eigen::MatrixXd& x, const Eigen::MatrixXd& v);

/// Polar retraction, block by block: (Z Zᵀ)^(−½) Z with Z = X_i + V_i.
Eigen::MatrixXd Retract(const Eigen::MatrixXd& x, const Eigen::MatrixXd& v);

/// Lagrange multipliers Λ_i = sym((QX)_i X_iᵀ) of the orthonormality constraints.
MultiplierBlocks Multipliers(const Eigen::MatrixXd& x, const Eigen::MatrixXd& qx);

/// (Q − Diag(Λ)) V: the certificate matrix S applied to V (3n × k).
Eigen::MatrixXd CertificateProduct(const RotationForm& form, const MultiplierBlocks& lambda,
                                   const Eigen::MatrixXd& v);

/// Frobenius inner product, the Riemannian metric.
double Inner(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

/// A point of the lifted problem with what the optimiser needs there.
struct Point {
  Point(const RotationForm& form, Eigen::MatrixXd at);

  /// Riemannian Hessian applied to a tangent vector: 2 Proj_X((Q − Diag(Λ)) V).
  Eigen::MatrixXd Hessian(const RotationForm& form, const Eigen::MatrixXd& v) const;

  Eigen::MatrixXd x, qx;     ///< X and Q X
  MultiplierBlocks lambda;   ///< Λ(X)
  Eigen::MatrixXd gradient;  ///< Riemannian gradient 2 (QX − Diag(Λ) X)
  double cost = 0.0;         ///< tr(XᵀQX) + c
};

}  // namespace sewer3d::lifted
