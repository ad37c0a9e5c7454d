#include "sewer3d/register/information.hpp"

#include <Eigen/Eigenvalues>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"

namespace sewer3d {
namespace {

Vector6d Scales(double length_scale_mm) {
  Vector6d s;
  s << 1.0, 1.0, 1.0, 1.0 / length_scale_mm, 1.0 / length_scale_mm, 1.0 / length_scale_mm;
  return s;
}

}  // namespace

Rigid3d ApplyUpdate(const Rigid3d& a_from_b, const Vector6d& delta) {
  const Eigen::Vector3d w = delta.tail<3>();
  const double angle = w.norm();
  const Eigen::Quaterniond dq = angle > 0.0
                                    ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle))
                                    : Eigen::Quaterniond::Identity();
  return {dq * a_from_b.rotation, a_from_b.translation + delta.head<3>()};
}

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

Matrix6d ToResidualOrder(const Matrix6d& hessian) {
  Matrix6d out = hessian;
  out.topRightCorner<3, 3>() *= -1.0;
  out.bottomLeftCorner<3, 3>() *= -1.0;
  return 0.5 * (out + out.transpose());
}

InformationSpectrum AnalyseInformation(const Matrix6d& information, double length_scale_mm,
                                       double degeneracy_ratio) {
  SEWER3D_CHECK(length_scale_mm > 0.0);
  InformationSpectrum out;
  out.length_scale_mm = length_scale_mm;
  const Vector6d s = Scales(length_scale_mm);
  const Matrix6d scaled = s.asDiagonal() * information * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(0.5 * (scaled + scaled.transpose()));
  out.eigenvalues = eig.eigenvalues();
  out.eigenvectors = eig.eigenvectors();
  const double largest = out.eigenvalues(5);
  out.ratio = largest > 0.0 ? std::max(0.0, out.eigenvalues(0)) / largest : 0.0;
  out.degenerate = out.ratio < degeneracy_ratio;
  // v_s = S⁻¹ v: a unit step in the scaled coordinates is (δt, L·δθ).
  out.weak_direction = s.asDiagonal() * out.eigenvectors.col(0);
  return out;
}

double RelativeInformationAlong(const InformationSpectrum& spectrum, const Matrix6d& information,
                                const Vector6d& direction) {
  const Vector6d s = Scales(spectrum.length_scale_mm);
  const Vector6d unit_scaled = s.cwiseInverse().cwiseProduct(direction).normalized();
  const Vector6d v = s.cwiseProduct(unit_scaled);  // back in (mm, rad)
  const double largest = spectrum.eigenvalues(5);
  return largest > 0.0 ? v.dot(information * v) / largest : 0.0;
}

Matrix6d WithCovarianceFloor(const Matrix6d& information, double sigma_t_mm, double sigma_r_deg) {
  if (sigma_t_mm <= 0.0 && sigma_r_deg <= 0.0) return information;
  // Ω = S⁻¹ V Λ Vᵀ S⁻¹ with S the arc metric (any L: the range does not depend on it, only
  // the threshold's sense of "small" does). y = Vᵀ S⁻¹ δ has covariance Λ⁻¹ on the kept
  // eigenvectors; the floor F on δ adds Vᵀ S⁻¹ F S⁻¹ V there.
  constexpr double kLengthMm = 100.0;
  const Vector6d s = Scales(kLengthMm);
  const Matrix6d scaled = s.asDiagonal() * information * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(0.5 * (scaled + scaled.transpose()));
  const double largest = eig.eigenvalues()(5);
  if (!(largest > 0.0)) return Matrix6d::Zero();
  int first = 0;
  while (first < 6 && !(eig.eigenvalues()(first) > 1e-12 * largest)) ++first;
  const int k = 6 - first;
  const Eigen::MatrixXd v = eig.eigenvectors().rightCols(k);
  const double arc_mm = kLengthMm * sigma_r_deg * kRadPerDeg;
  Vector6d floor_scaled;
  floor_scaled << Eigen::Vector3d::Constant(sigma_t_mm * sigma_t_mm),
      Eigen::Vector3d::Constant(arc_mm * arc_mm);
  const Eigen::MatrixXd cov =
      Eigen::MatrixXd(eig.eigenvalues().tail(k).cwiseInverse().asDiagonal()) +
      v.transpose() * floor_scaled.asDiagonal() * v;
  const Eigen::MatrixXd w = s.cwiseInverse().asDiagonal() * v;  // S⁻¹ V
  const Matrix6d out = w * cov.inverse() * w.transpose();
  return 0.5 * (out + out.transpose());
}

}  // namespace sewer3d
