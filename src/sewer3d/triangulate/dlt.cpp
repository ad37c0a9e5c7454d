#include "sewer3d/triangulate/dlt.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace sewer3d {

std::optional<Eigen::Vector3d> TriangulateDlt(const Eigen::Vector2d& camera_xy,
                                              const Eigen::Vector2d& projector_xy,
                                              const Rigid3d& projector_from_camera) {
  Eigen::Matrix<double, 3, 4> p_projector;
  p_projector.leftCols<3>() = projector_from_camera.RotationMatrix();
  p_projector.col(3) = projector_from_camera.translation;
  return TriangulateDlt(camera_xy, projector_xy, p_projector);
}

std::optional<Eigen::Vector3d> TriangulateDlt(const Eigen::Vector2d& camera_xy,
                                              const Eigen::Vector2d& projector_xy,
                                              const Eigen::Matrix<double, 3, 4>& p_projector) {
  Eigen::Matrix<double, 3, 4> p_camera = Eigen::Matrix<double, 3, 4>::Zero();
  p_camera.leftCols<3>().setIdentity();
  // x (p3ᵀ X) − p1ᵀ X = 0 and y (p3ᵀ X) − p2ᵀ X = 0 for each view.
  Eigen::Matrix4d a;
  a.row(0) = camera_xy.x() * p_camera.row(2) - p_camera.row(0);
  a.row(1) = camera_xy.y() * p_camera.row(2) - p_camera.row(1);
  a.row(2) = projector_xy.x() * p_projector.row(2) - p_projector.row(0);
  a.row(3) = projector_xy.y() * p_projector.row(2) - p_projector.row(1);
  // Equilibrate rows so neither view dominates through scale alone.
  for (int i = 0; i < 4; ++i) a.row(i) /= std::max(a.row(i).norm(), 1e-300);
  // The right singular vector of the smallest singular value of A is the eigenvector of the
  // smallest eigenvalue of M = AᵀA. Inverse iteration finds it: start from the inhomogeneous
  // solution (last coordinate 1), then x ← M⁻¹ x; each step shrinks the other components by
  // (σ₄/σᵢ)², about 1e-6 for a two-view DLT, so two steps reach the SVD's answer to rounding
  // at a fraction of a 4 x 4 Jacobi SVD's cost.
  const Eigen::Matrix4d m = a.transpose() * a;
  const Eigen::LDLT<Eigen::Matrix3d> inhomogeneous(m.topLeftCorner<3, 3>());
  Eigen::Vector4d x;
  x << -inhomogeneous.solve(m.topRightCorner<3, 1>()), 1.0;
  // LU without rank thresholding (LDLT would zero the tiny pivot that carries the answer).
  const Eigen::PartialPivLU<Eigen::Matrix4d> solver(m);
  for (int iteration = 0; iteration < 2; ++iteration) {
    const Eigen::Vector4d next = solver.solve(x);
    if (!next.allFinite() || next.norm() == 0.0) break;
    x = next.normalized();
  }
  if (std::abs(x.w()) < 1e-12 * x.head<3>().norm()) return std::nullopt;  // point at infinity
  const Eigen::Vector3d point = x.head<3>() / x.w();
  if (!(point.z() > 0.0) || !(p_projector.row(2).head<3>().dot(point) + p_projector(2, 3) > 0.0)) {
    return std::nullopt;
  }
  return point;
}

std::optional<Eigen::Vector3d> TriangulateOnProjectorRay(
    const Eigen::Vector2d& camera_xy, const Eigen::Vector2d& projector_xy,
    const Eigen::Matrix<double, 3, 4>& p_projector) {
  // Projector centre C = -Rᵀt and ray direction D = Rᵀ(x, y, 1) in the camera frame; their
  // images span the epipolar line l = C × D (homogeneous, normalised camera coordinates).
  const Eigen::Matrix3d r_transpose = p_projector.leftCols<3>().transpose();
  const Eigen::Vector3d centre = -r_transpose * p_projector.col(3);
  const Eigen::Vector3d direction = r_transpose * projector_xy.homogeneous();
  const Eigen::Vector3d line = centre.cross(direction);
  const double normal2 = line.head<2>().squaredNorm();
  if (!(normal2 > 0.0)) return std::nullopt;  // the ray passes through the camera centre
  const double distance = line.dot(camera_xy.homogeneous()) / normal2;
  const Eigen::Vector2d on_line = camera_xy - distance * line.head<2>();
  return TriangulateDlt(on_line, projector_xy, p_projector);
}

}  // namespace sewer3d
