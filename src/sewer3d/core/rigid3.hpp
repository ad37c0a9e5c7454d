#pragma once
/// \file
/// Rigid3d: a rigid transform (unit quaternion + translation). Naming follows the frames:
/// `b_from_a` maps a point expressed in frame a into frame b: p_b = b_from_a * p_a.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sewer3d {

/// A rigid transform p_out = rotation * p_in + translation (lengths in mm).
/// The quaternion is kept unit-norm by every constructor and operation here.
struct Rigid3d {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Rigid3d() = default;
  Rigid3d(const Eigen::Quaterniond& q, const Eigen::Vector3d& t)
      : rotation(q.normalized()), translation(t) {}
  Rigid3d(const Eigen::Matrix3d& r, const Eigen::Vector3d& t) : rotation(r), translation(t) {
    rotation.normalize();
  }

  static Rigid3d Identity() { return {}; }

  Eigen::Matrix3d RotationMatrix() const { return rotation.toRotationMatrix(); }

  Rigid3d Inverse() const {
    const Eigen::Quaterniond inv = rotation.conjugate();
    return {inv, -(inv * translation)};
  }

  Eigen::Vector3d operator*(const Eigen::Vector3d& p) const { return rotation * p + translation; }

  /// Composition: (c_from_b * b_from_a) = c_from_a.
  Rigid3d operator*(const Rigid3d& other) const {
    return {rotation * other.rotation, rotation * other.translation + translation};
  }
};

}  // namespace sewer3d
