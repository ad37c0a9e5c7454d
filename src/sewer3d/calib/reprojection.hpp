#pragma once
/// \file
/// Internal to calib/: the reprojection residual of a board point (Ceres, autodiff).

#include <ceres/rotation.h>

#include <Eigen/Core>

namespace sewer3d {

// Residual of the module file's camera model, x_d = x (1 + k1 r² + k2 r⁴ + k3 r⁶), for a
// point p in the camera's frame observed at `observed`.
template <typename T>
void ProjectionResidual(const T* focal_centre, const T* k, const T* p,
                        const Eigen::Vector2d& observed, T* residual) {
  const T x = p[0] / p[2], y = p[1] / p[2];
  const T r2 = x * x + y * y;
  const T d = T(1.0) + r2 * (k[0] + r2 * (k[1] + r2 * k[2]));
  residual[0] = focal_centre[0] * x * d + focal_centre[2] - T(observed.x());
  residual[1] = focal_centre[1] * y * d + focal_centre[3] - T(observed.y());
}

// A board point seen by the camera: board pose as angle-axis + translation.
struct ReprojectionCost {
  Eigen::Vector3d board;
  Eigen::Vector2d observed;

  template <typename T>
  bool operator()(const T* focal_centre, const T* k, const T* rotation, const T* translation,
                  T* residual) const {
    const T point[3] = {T(board.x()), T(board.y()), T(board.z())};
    T p[3];
    ceres::AngleAxisRotatePoint(rotation, point, p);
    for (int i = 0; i < 3; ++i) p[i] += translation[i];
    ProjectionResidual(focal_centre, k, p, observed, residual);
    return true;
  }
};

// A board point seen by the projector (an inverse camera): board -> camera by the view's
// pose, camera -> projector by the module's extrinsics.
struct StereoReprojectionCost {
  Eigen::Vector3d board;
  Eigen::Vector2d observed;

  template <typename T>
  bool operator()(const T* focal_centre, const T* k, const T* view_rotation,
                  const T* view_translation, const T* rotation, const T* translation,
                  T* residual) const {
    const T point[3] = {T(board.x()), T(board.y()), T(board.z())};
    T c[3], p[3];
    ceres::AngleAxisRotatePoint(view_rotation, point, c);
    for (int i = 0; i < 3; ++i) c[i] += view_translation[i];
    ceres::AngleAxisRotatePoint(rotation, c, p);
    for (int i = 0; i < 3; ++i) p[i] += translation[i];
    ProjectionResidual(focal_centre, k, p, observed, residual);
    return true;
  }
};

}  // namespace sewer3d
