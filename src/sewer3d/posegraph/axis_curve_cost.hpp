#pragma once
/// \file
/// Ceres functors of the centreline's terms (axis_curve.hpp), templated so that the residual
/// functions of axis_curve.cpp (double) and the solver (Jets) share one formula.

#include <ceres/autodiff_cost_function.h>
#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sewer3d/posegraph/axis_curve.hpp"

namespace sewer3d {

/// [(I − T Tᵀ) d / σ ; Tᵀ d / σ_along] for d, T given (T is normalised here).
template <typename T>
Eigen::Matrix<T, 4, 1> SplitAlong(const Eigen::Matrix<T, 3, 1>& d,
                                  const Eigen::Matrix<T, 3, 1>& direction, double sigma,
                                  double along_sigma) {
  const Eigen::Matrix<T, 3, 1> unit = direction / direction.norm();
  const T along = unit.dot(d);
  Eigen::Matrix<T, 4, 1> r;
  r.template head<3>() = (d - along * unit) / T(sigma);
  r[3] = along / T(along_sigma);
  return r;
}

/// An axis observation: parameters p (3), q (4, x y z w) of the node and the two control points
/// of its segment (3 each); the weight f of the second is fixed at construction.
class AxisCost {
 public:
  AxisCost(const AxisObservation& observation, double fraction)
      : in_node_(observation.in_node),
        fraction_(fraction),
        sigma_(observation.sigma_mm),
        along_sigma_(observation.along_sigma_mm) {}

  template <typename T>
  bool operator()(const T* p_ptr, const T* q_ptr, const T* c0_ptr, const T* c1_ptr,
                  T* residuals_ptr) const {
    Eigen::Map<const Eigen::Matrix<T, 3, 1>> p(p_ptr), c0(c0_ptr), c1(c1_ptr);
    Eigen::Map<const Eigen::Quaternion<T>> q(q_ptr);
    const Eigen::Matrix<T, 3, 1> world = q * in_node_.template cast<T>() + p;
    const Eigen::Matrix<T, 3, 1> on_curve = c0 + T(fraction_) * (c1 - c0);
    Eigen::Map<Eigen::Matrix<T, 4, 1>> residuals(residuals_ptr);
    residuals = SplitAlong<T>(world - on_curve, c1 - c0, sigma_, along_sigma_);
    return true;
  }

  static ceres::CostFunction* Create(const AxisObservation& observation, double fraction) {
    return new ceres::AutoDiffCostFunction<AxisCost, 4, 3, 4, 3, 3>(
        new AxisCost(observation, fraction));
  }

 private:
  Eigen::Vector3d in_node_;
  double fraction_, sigma_, along_sigma_;
};

/// The second difference of three consecutive control points (3 each).
class CurvatureCost {
 public:
  CurvatureCost(double sigma, double along_sigma) : sigma_(sigma), along_sigma_(along_sigma) {}

  template <typename T>
  bool operator()(const T* c0_ptr, const T* c1_ptr, const T* c2_ptr, T* residuals_ptr) const {
    Eigen::Map<const Eigen::Matrix<T, 3, 1>> c0(c0_ptr), c1(c1_ptr), c2(c2_ptr);
    Eigen::Map<Eigen::Matrix<T, 4, 1>> residuals(residuals_ptr);
    residuals = SplitAlong<T>(c2 - T(2) * c1 + c0, c2 - c0, sigma_, along_sigma_);
    return true;
  }

  static ceres::CostFunction* Create(double sigma, double along_sigma) {
    return new ceres::AutoDiffCostFunction<CurvatureCost, 4, 3, 3, 3>(
        new CurvatureCost(sigma, along_sigma));
  }

 private:
  double sigma_, along_sigma_;
};

}  // namespace sewer3d
