#pragma once
/// \file
/// Information matrices of pairwise registrations in the pose graph's residual order, and
/// their spectrum (which directions the data constrain).
///
/// Convention of both registrations' Gauss–Newton (feature_registration.hpp,
/// projection_registration.hpp): the estimate of a_from_b = (R, t) is updated as
///   R ← Exp(δθ) R,  t ← t + δt,  δ = (δt, δθ) expressed in a's frame,
/// so a point x_b of b maps to x_a = R x_b + t with ∂x_a/∂δ = [I, −[R x_b]×]. The Gauss–Newton
/// Hessian H = Σ Jᵀ W J is the information of the estimate's error δ (covariance H⁻¹).
///
/// The pose graph's residual (posegraph/pose_graph.hpp) r = [R_aᵀ(p_b − p_a) − p̂_ab ;
/// 2 vec(q̂_ab q_ab⁻¹)] evaluated at the true poses, with the measurement p̂ = p + δt,
/// q̂ = Exp(δθ) q, is r = [−δt ; δθ] to first order. Hence Cov(r) = D H⁻¹ D and the edge's
/// information is D H D with D = diag(−I₃, I₃): the translation–rotation blocks change sign.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sewer3d/posegraph/pose_graph.hpp"

namespace sewer3d {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// The update of the convention above: (Exp(δθ) R, t + δt) for δ = (δt, δθ).
Rigid3d ApplyUpdate(const Rigid3d& a_from_b, const Vector6d& delta);

/// [v]×: Skew(v) w = v × w.
Eigen::Matrix3d Skew(const Eigen::Vector3d& v);

/// D H D, D = diag(−I₃, I₃): the Hessian of δ = (δt, δθ) as the information of the pose
/// graph's residual (see the file comment). Symmetrised.
Matrix6d ToResidualOrder(const Matrix6d& hessian);

/// The information of covariance Ω⁺ + diag(σt², σt², σt², σr², σr², σr²) within the range of
/// Ω (residual order, σr in degrees as a small rotation's angle): U (Λ⁻¹ + Uᵀ F U)⁻¹ Uᵀ with
/// U, Λ the eigenvectors and eigenvalues of Ω above 1e-12 of the largest. Directions without
/// information keep none; where Ω has full rank this is (Ω⁻¹ + F)⁻¹. A floor stands for what
/// more measurements do not average away (biases shared by the whole overlap).
Matrix6d WithCovarianceFloor(const Matrix6d& information, double sigma_t_mm, double sigma_r_deg);

/// The registrations' default floor (σ per translation axis, mm; per rotation axis, degrees):
/// measured on simulated runs with modules calibrated as a real build is (the `paper` profile:
/// each module's own focal, centre and baseline error and lens residual bias a pair's relative
/// pose alike for all its matches), where it puts the edges' mean NEES in [3, 12]
/// (docs/registration.md, "Information under the paper profile").
inline constexpr double kFloorTranslationMm = 0.15;
inline constexpr double kFloorRotationDeg = 0.04;

/// Eigen-decomposition of an information matrix with rotations expressed as arc lengths at a
/// characteristic distance L (the scene's distance from the camera), so that translation and
/// rotation are comparable: Ω_s = S Ω S, S = diag(1, 1, 1, 1/L, 1/L, 1/L) (units 1/mm²).
struct InformationSpectrum {
  double length_scale_mm = 1.0;             ///< L
  Vector6d eigenvalues = Vector6d::Zero();  ///< of Ω_s, ascending, 1/mm²
  /// Unit eigenvectors of Ω_s (columns, as eigenvalues), in (mm, L·rad) coordinates.
  Matrix6d eigenvectors = Matrix6d::Identity();
  double ratio = 0.0;       ///< smallest / largest eigenvalue (0 when the largest is ≤ 0)
  bool degenerate = false;  ///< ratio below the threshold given
  /// The least constrained direction: eigenvectors.col(0) turned back into (δt mm, δθ rad) of
  /// the residual order, scaled to unit norm in the (mm, L·rad) metric.
  Vector6d weak_direction = Vector6d::Zero();
};

/// Spectrum of `information` (residual order) at length scale `length_scale_mm` (> 0);
/// `degenerate` when ratio < `degeneracy_ratio`.
InformationSpectrum AnalyseInformation(const Matrix6d& information, double length_scale_mm,
                                       double degeneracy_ratio);

/// vᵀ Ω v / λ_max(Ω_s) for a direction v = (δt mm, δθ rad) in residual order, with v measured
/// in the (mm, L·rad) metric: how much of the strongest constraint acts along v (0: none).
double RelativeInformationAlong(const InformationSpectrum& spectrum, const Matrix6d& information,
                                const Vector6d& direction);

}  // namespace sewer3d
