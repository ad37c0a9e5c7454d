#include "sewer3d/triangulate/dlt.hpp"

#include <Eigen/SVD>

namespace sewer3d {

std::optional<Eigen::Vector3d> TriangulateDlt(const Eigen::Vector2d& camera_xy,
                                              const Eigen::Vector2d& projector_xy,
                                              const Rigid3d& projector_from_camera) {
  Eigen::Matrix<double, 3, 4> p_camera = Eigen::Matrix<double, 3, 4>::Zero();
  p_camera.leftCols<3>().setIdentity();
  Eigen::Matrix<double, 3, 4> p_projector;
  p_projector.leftCols<3>() = projector_from_camera.RotationMatrix();
  p_projector.col(3) = projector_from_camera.translation;
  // x (p3ᵀ X) − p1ᵀ X = 0 and y (p3ᵀ X) − p2ᵀ X = 0 for each view.
  Eigen::Matrix4d a;
  a.row(0) = camera_xy.x() * p_camera.row(2) - p_camera.row(0);
  a.row(1) = camera_xy.y() * p_camera.row(2) - p_camera.row(1);
  a.row(2) = projector_xy.x() * p_projector.row(2) - p_projector.row(0);
  a.row(3) = projector_xy.y() * p_projector.row(2) - p_projector.row(1);
  // Equilibrate rows so neither view dominates through scale alone.
  for (int i = 0; i < 4; ++i) a.row(i) /= std::max(a.row(i).norm(), 1e-300);
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(a, Eigen::ComputeFullV);
  const Eigen::Vector4d x = svd.matrixV().col(3);
  if (std::abs(x.w()) < 1e-12 * x.head<3>().norm()) return std::nullopt;  // point at infinity
  const Eigen::Vector3d point = x.head<3>() / x.w();
  if (!(point.z() > 0.0) || !((projector_from_camera * point).z() > 0.0)) return std::nullopt;
  return point;
}

}  // namespace sewer3d
