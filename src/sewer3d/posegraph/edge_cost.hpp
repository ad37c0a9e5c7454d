#pragma once
/// \file
/// The pose-graph residual as a Ceres auto-differentiated functor (paper eq. for the pose
/// graph; Ceres' examples/slam/pose_graph_3d): parameters p_a (3), q_a (4, x y z w),
/// p_b (3), q_b (4); residual sqrt(Ω) [R_aᵀ (p_b − p_a) − p̂_ab ; ±2 vec(q̂_ab (q_a⁻¹ q_b)⁻¹)], the
/// sign making the error quaternion's w non-negative.

#include <ceres/autodiff_cost_function.h>
#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <utility>
#include <vector>

#include "sewer3d/posegraph/pose_graph.hpp"

namespace sewer3d {

class EdgeCost {
 public:
  EdgeCost(const Rigid3d& a_from_b, const Matrix6d& sqrt_information)
      : p_ab_(a_from_b.translation),
        q_ab_(a_from_b.rotation),
        sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* p_a_ptr, const T* q_a_ptr, const T* p_b_ptr, const T* q_b_ptr,
                  T* residuals_ptr) const {
    Eigen::Map<Eigen::Matrix<T, 6, 1>> residuals(residuals_ptr);
    residuals = Weighted(Unweighted(p_a_ptr, q_a_ptr, p_b_ptr, q_b_ptr));
    return true;
  }

  /// [R_aᵀ (p_b − p_a) − p̂_ab ; ±2 vec(q̂_ab (q_a⁻¹ q_b)⁻¹)], before the weight.
  template <typename T>
  Eigen::Matrix<T, 6, 1> Unweighted(const T* p_a_ptr, const T* q_a_ptr, const T* p_b_ptr,
                                    const T* q_b_ptr) const {
    Eigen::Map<const Eigen::Matrix<T, 3, 1>> p_a(p_a_ptr), p_b(p_b_ptr);
    Eigen::Map<const Eigen::Quaternion<T>> q_a(q_a_ptr), q_b(q_b_ptr);
    const Eigen::Quaternion<T> q_a_inverse = q_a.conjugate();
    const Eigen::Quaternion<T> q_ab_estimated = q_a_inverse * q_b;
    const Eigen::Matrix<T, 3, 1> p_ab_estimated = q_a_inverse * (p_b - p_a);
    const Eigen::Quaternion<T> delta_q = q_ab_.template cast<T>() * q_ab_estimated.conjugate();
    Eigen::Matrix<T, 6, 1> residuals;
    residuals.template head<3>() = p_ab_estimated - p_ab_.template cast<T>();
    // q and -q are the same rotation: take the error quaternion with w >= 0, so that a file
    // (or a solver step) writing either sign gets the same cost.
    const T sign = delta_q.w() < T(0) ? T(-2.0) : T(2.0);
    residuals.template tail<3>() = sign * delta_q.vec();
    return residuals;
  }

  template <typename T>
  Eigen::Matrix<T, 6, 1> Weighted(const Eigen::Matrix<T, 6, 1>& r) const {
    return sqrt_information_.template cast<T>() * r;
  }

  /// sqrt_information: upper-triangular S with SᵀS = Ω.
  static ceres::CostFunction* Create(const Rigid3d& a_from_b, const Matrix6d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<EdgeCost, 6, 3, 4, 3, 4>(
        new EdgeCost(a_from_b, sqrt_information));
  }

 private:
  Eigen::Vector3d p_ab_;
  Eigen::Quaterniond q_ab_;
  Matrix6d sqrt_information_;
};

/// An edge whose measurement shares a bias with its group (PoseEdge::bias): the residual
/// S (r − b), with b a sixth parameter block of 6.
class BiasedEdgeCost {
 public:
  BiasedEdgeCost(const Rigid3d& a_from_b, const Matrix6d& sqrt_information)
      : edge_(a_from_b, sqrt_information) {}

  template <typename T>
  bool operator()(const T* p_a_ptr, const T* q_a_ptr, const T* p_b_ptr, const T* q_b_ptr,
                  const T* bias_ptr, T* residuals_ptr) const {
    Eigen::Map<const Eigen::Matrix<T, 6, 1>> bias(bias_ptr);
    Eigen::Map<Eigen::Matrix<T, 6, 1>> residuals(residuals_ptr);
    residuals = edge_.Weighted<T>(edge_.Unweighted(p_a_ptr, q_a_ptr, p_b_ptr, q_b_ptr) - bias);
    return true;
  }

  static ceres::CostFunction* Create(const Rigid3d& a_from_b, const Matrix6d& sqrt_information) {
    return new ceres::AutoDiffCostFunction<BiasedEdgeCost, 6, 3, 4, 3, 4, 6>(
        new BiasedEdgeCost(a_from_b, sqrt_information));
  }

 private:
  EdgeCost edge_;
};

/// S Σ A_k b_k over several bias blocks of 6 (PoseGraph::AddZeroSum): linear, Jacobian S A_k.
class BiasSumCost : public ceres::CostFunction {
 public:
  BiasSumCost(std::vector<Matrix6d> frames, const Matrix6d& sqrt_information)
      : frames_(std::move(frames)), sqrt_information_(sqrt_information) {
    set_num_residuals(6);
    for (size_t i = 0; i < frames_.size(); ++i) mutable_parameter_block_sizes()->push_back(6);
  }
  bool Evaluate(double const* const* parameters, double* residuals_ptr,
                double** jacobians) const override {
    Eigen::Matrix<double, 6, 1> sum = Eigen::Matrix<double, 6, 1>::Zero();
    for (size_t i = 0; i < frames_.size(); ++i)
      sum += frames_[i] * Eigen::Map<const Eigen::Matrix<double, 6, 1>>(parameters[i]);
    Eigen::Map<Eigen::Matrix<double, 6, 1>> residuals(residuals_ptr);
    residuals = sqrt_information_ * sum;
    if (jacobians == nullptr) return true;
    for (size_t i = 0; i < frames_.size(); ++i) {
      if (jacobians[i] == nullptr) continue;
      Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>> jacobian(jacobians[i]);
      jacobian = sqrt_information_ * frames_[i];
    }
    return true;
  }

 private:
  std::vector<Matrix6d> frames_;
  Matrix6d sqrt_information_;
};

/// A direction observation (PoseGraph::AddDirection): parameters q (4, x y z w) of the node and
/// the world direction g (3, on the unit sphere); residual (R(q) d − g) / σ.
class DirectionCost {
 public:
  DirectionCost(const Eigen::Vector3d& in_node, double sigma_rad)
      : in_node_(in_node), inverse_sigma_(1.0 / sigma_rad) {}

  template <typename T>
  bool operator()(const T* q_ptr, const T* g_ptr, T* residuals_ptr) const {
    Eigen::Map<const Eigen::Quaternion<T>> q(q_ptr);
    Eigen::Map<const Eigen::Matrix<T, 3, 1>> g(g_ptr);
    Eigen::Map<Eigen::Matrix<T, 3, 1>> residuals(residuals_ptr);
    residuals = (q * in_node_.template cast<T>() - g) * T(inverse_sigma_);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& in_node, double sigma_rad) {
    return new ceres::AutoDiffCostFunction<DirectionCost, 3, 4, 3>(
        new DirectionCost(in_node, sigma_rad));
  }

 private:
  Eigen::Vector3d in_node_;
  double inverse_sigma_;
};

/// Upper-triangular S with SᵀS = Ω (Cholesky).
Matrix6d SqrtInformation(const Matrix6d& information);

}  // namespace sewer3d
