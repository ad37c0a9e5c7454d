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
  double weight = 1.0;  ///< residual scale: 1 / the corners' noise (px) in a weighted problem

  template <typename T>
  bool operator()(const T* focal_centre, const T* k, const T* rotation, const T* translation,
                  T* residual) const {
    const T point[3] = {T(board.x()), T(board.y()), T(board.z())};
    T p[3];
    ceres::AngleAxisRotatePoint(rotation, point, p);
    for (int i = 0; i < 3; ++i) p[i] += translation[i];
    ProjectionResidual(focal_centre, k, p, observed, residual);
    residual[0] *= weight;
    residual[1] *= weight;
    return true;
  }
};

// A board point seen by the projector (an inverse camera): board -> camera by the view's
// pose, camera -> projector by the module's extrinsics.
struct StereoReprojectionCost {
  Eigen::Vector3d board;
  Eigen::Vector2d observed;
  double weight = 1.0;  ///< as ReprojectionCost's

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
    residual[0] *= weight;
    residual[1] *= weight;
    return true;
  }
};

// Poses as Ceres parameters: angle-axis (3) then translation (3).
inline std::array<double, 6> AngleAxisOf(const Rigid3d& pose) {
  const Eigen::AngleAxisd aa(pose.rotation);
  const Eigen::Vector3d r = aa.angle() * aa.axis();
  return {r.x(), r.y(), r.z(), pose.translation.x(), pose.translation.y(), pose.translation.z()};
}

inline Rigid3d PoseFromAngleAxis(const double* p) {
  const Eigen::Vector3d r(p[0], p[1], p[2]);
  const double angle = r.norm();
  const Eigen::Quaterniond q(angle > 0 ? Eigen::AngleAxisd(angle, r / angle)
                                       : Eigen::AngleAxisd::Identity());
  return {q, Eigen::Vector3d(p[3], p[4], p[5])};
}

// Intrinsics from the parameter blocks (fx, fy, cx, cy) and (k1, k2, k3).
inline CameraIntrinsics IntrinsicsFrom(const double* focal_centre, const double* k, int width,
                                       int height) {
  CameraIntrinsics c;
  c.width = width;
  c.height = height;
  c.fx = focal_centre[0], c.fy = focal_centre[1], c.cx = focal_centre[2], c.cy = focal_centre[3];
  c.k = {k[0], k[1], k[2]};
  return c;
}

// Levenberg–Marquardt to tight tolerances (calibration problems are small); returns the
// iterations taken and whether Ceres reported convergence.
inline std::pair<int, bool> SolveCalibration(ceres::Problem& problem, int max_iterations) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_SCHUR;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return {static_cast<int>(summary.iterations.size()) - 1,
          summary.termination_type == ceres::CONVERGENCE};
}

}  // namespace sewer3d
