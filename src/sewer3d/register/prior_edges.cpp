#include "sewer3d/register/prior_edges.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

const Rigid3d& CarrierFromCamera(const Rig& rig, int module) {
  SEWER3D_VALIDATE(module >= 0 && module < static_cast<int>(rig.modules.size()), "module",
                   "node names module " << module << ", the rig has " << rig.modules.size());
  return rig.modules[module].carrier_from_camera;
}

Matrix6d Diagonal(double lateral_mm, double along_mm, double tilt_rad, double roll_rad) {
  Vector6d d;
  d << lateral_mm, lateral_mm, along_mm, tilt_rad, tilt_rad, roll_rad;
  return d.cwiseAbs2().asDiagonal();
}

Matrix6d Information(const Matrix6d& covariance) {
  const Matrix6d symmetric = 0.5 * (covariance + covariance.transpose());
  Matrix6d information = symmetric.inverse();
  return 0.5 * (information + information.transpose());
}

/// The edge C_a⁻¹ · M · C_b with M = translation along the carrier axis by d_b − d_a.
RegistrationEdge CarrierEdge(const std::vector<AcquisitionNode>& nodes, const Rig& rig, int a,
                             int b, RegistrationEdgeType type, const Matrix6d& carrier_covariance,
                             const Matrix6d& camera_covariance) {
  const Rigid3d& ca = CarrierFromCamera(rig, nodes[a].module);
  const Rigid3d& cb = CarrierFromCamera(rig, nodes[b].module);
  const Rigid3d motion(Eigen::Quaterniond::Identity(),
                       Eigen::Vector3d(0, 0, nodes[b].distance_mm - nodes[a].distance_mm));
  RegistrationEdge edge;
  edge.a = a;
  edge.b = b;
  edge.type = type;
  edge.a_from_b = ca.Inverse() * motion * cb;
  edge.information = Information(CameraCovarianceFromCarrier(ca, motion, cb, carrier_covariance) +
                                 camera_covariance);
  return edge;
}

/// Node indices per key (module or counter), each list ordered by the other.
std::map<int, std::vector<int>> GroupBy(const std::vector<AcquisitionNode>& nodes, bool by_module) {
  std::map<int, std::vector<int>> groups;
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i)
    groups[by_module ? nodes[i].module : nodes[i].counter].push_back(i);
  for (auto& [key, list] : groups) {
    std::sort(list.begin(), list.end(), [&](int x, int y) {
      return by_module ? nodes[x].counter < nodes[y].counter : nodes[x].module < nodes[y].module;
    });
  }
  return groups;
}

}  // namespace

const char* RegistrationEdgeTypeName(RegistrationEdgeType type) {
  switch (type) {
    case RegistrationEdgeType::kFeature:
      return "feature";
    case RegistrationEdgeType::kProjection:
      return "projection";
    case RegistrationEdgeType::kRig:
      return "rig";
    case RegistrationEdgeType::kOdometry:
      return "odometry";
    case RegistrationEdgeType::kStraightness:
      return "straightness";
  }
  return "?";
}

bool IsPairwiseEdge(RegistrationEdgeType type) {
  return type == RegistrationEdgeType::kFeature || type == RegistrationEdgeType::kProjection;
}

void PriorEdgeOptions::Check() const {
  ValidatePositive("rig_sigma_mm", rig_sigma_mm);
  ValidatePositive("rig_sigma_deg", rig_sigma_deg);
  ValidatePositive("odometry_noise_mm", odometry_noise_mm);
  ValidateNotNegative("odometry_scale_sigma", odometry_scale_sigma);
  ValidateNotNegative("lateral_speed_mm_s", lateral_speed_mm_s);
  ValidateNotNegative("turn_rate_deg_s", turn_rate_deg_s);
  ValidatePositive("odometry_lateral_sigma_mm", odometry_lateral_sigma_mm);
  ValidatePositive("odometry_rotation_sigma_deg", odometry_rotation_sigma_deg);
  ValidatePositive("min_bend_radius_mm", min_bend_radius_mm);
  ValidatePositive("carrier_wander_mm", carrier_wander_mm);
  ValidatePositive("carrier_wobble_deg", carrier_wobble_deg);
  ValidatePositive("carrier_roll_deg", carrier_roll_deg);
}

Matrix6d CameraCovarianceFromCarrier(const Rigid3d& carrier_from_camera_a,
                                     const Rigid3d& carrier_a_from_carrier_b,
                                     const Rigid3d& carrier_from_camera_b,
                                     const Matrix6d& covariance_in_carrier) {
  const Eigen::Matrix3d ra_t = carrier_from_camera_a.RotationMatrix().transpose();
  const Eigen::Vector3d lever =
      carrier_a_from_carrier_b.rotation * carrier_from_camera_b.translation;
  Matrix6d j = Matrix6d::Zero();
  j.topLeftCorner<3, 3>() = ra_t;
  j.topRightCorner<3, 3>() = -ra_t * Skew(lever);
  j.bottomRightCorner<3, 3>() = ra_t;
  // (δt, δθ) of the camera pose → residual order [−δt; δθ] (information.hpp): D · D.
  return ToResidualOrder(j * covariance_in_carrier * j.transpose());
}

Matrix6d StraightnessCovariance(double length_mm, const PriorEdgeOptions& options) {
  const double l = std::abs(length_mm), r = options.min_bend_radius_mm;
  const double lateral = std::hypot(l * l / (2.0 * r), std::sqrt(2.0) * options.carrier_wander_mm);
  const double tilt = std::hypot(l / r, std::sqrt(2.0) * options.carrier_wobble_deg * kDegToRad);
  return Diagonal(lateral, l + 10.0, tilt, options.carrier_roll_deg * kDegToRad);
}

std::vector<RegistrationEdge> RigEdges(const std::vector<AcquisitionNode>& nodes, const Rig& rig,
                                       const PriorEdgeOptions& options) {
  options.Check();
  const Matrix6d calibration =
      2.0 * Diagonal(options.rig_sigma_mm, options.rig_sigma_mm, options.rig_sigma_deg * kDegToRad,
                     options.rig_sigma_deg * kDegToRad);
  std::vector<RegistrationEdge> edges;
  for (const auto& [counter, list] : GroupBy(nodes, false)) {
    for (size_t k = 0; k + 1 < list.size(); ++k) {
      const int a = list[k], b = list[k + 1];
      const double dt = std::abs(nodes[b].time_s - nodes[a].time_s);
      const double dd = std::abs(nodes[b].distance_mm - nodes[a].distance_mm);
      // In an odometry gap the carrier's speed, hence d_b − d_a, is uncertain.
      const double gap = std::max(nodes[a].speed_sigma_mm_s, nodes[b].speed_sigma_mm_s) * dt;
      const double along = dt > 0.0
                               ? std::hypot(std::hypot(std::sqrt(2.0) * options.odometry_noise_mm,
                                                       options.odometry_scale_sigma * dd),
                                            gap)
                               : 1e-3;
      const Matrix6d motion = Diagonal(std::max(options.lateral_speed_mm_s * dt, 1e-3), along,
                                       std::max(options.turn_rate_deg_s * dt, 1e-4) * kDegToRad,
                                       std::max(options.turn_rate_deg_s * dt, 1e-4) * kDegToRad);
      edges.push_back(
          CarrierEdge(nodes, rig, a, b, RegistrationEdgeType::kRig, motion, calibration));
    }
  }
  return edges;
}

std::vector<RegistrationEdge> OdometryEdges(const std::vector<AcquisitionNode>& nodes,
                                            const Rig& rig, const PriorEdgeOptions& options) {
  options.Check();
  std::vector<RegistrationEdge> edges;
  for (const auto& [module, list] : GroupBy(nodes, true)) {
    for (size_t k = 0; k + 1 < list.size(); ++k) {
      const int a = list[k], b = list[k + 1];
      const double dd = std::abs(nodes[b].distance_mm - nodes[a].distance_mm);
      // A distance interpolated across an odometry gap adds its σ (independent: conservative).
      const double along = std::sqrt(std::pow(std::sqrt(2.0) * options.odometry_noise_mm, 2) +
                                     std::pow(options.odometry_scale_sigma * dd, 2) +
                                     std::pow(nodes[a].distance_sigma_mm, 2) +
                                     std::pow(nodes[b].distance_sigma_mm, 2));
      const double turn = options.odometry_rotation_sigma_deg * kDegToRad;
      const Matrix6d motion = Diagonal(options.odometry_lateral_sigma_mm, along, turn, turn);
      edges.push_back(
          CarrierEdge(nodes, rig, a, b, RegistrationEdgeType::kOdometry, motion, Matrix6d::Zero()));
    }
  }
  return edges;
}

std::vector<RegistrationEdge> StraightnessEdges(const std::vector<AcquisitionNode>& nodes,
                                                const Rig& rig, const PriorEdgeOptions& options) {
  options.Check();
  std::vector<RegistrationEdge> edges;
  for (const auto& [module, list] : GroupBy(nodes, true)) {
    if (list.size() < 2) continue;
    const int a = list.front(), b = list.back();
    const Matrix6d prior =
        StraightnessCovariance(nodes[b].distance_mm - nodes[a].distance_mm, options);
    edges.push_back(CarrierEdge(nodes, rig, a, b, RegistrationEdgeType::kStraightness, prior,
                                Matrix6d::Zero()));
  }
  return edges;
}

std::vector<RegistrationEdge> PriorEdges(const std::vector<AcquisitionNode>& nodes, const Rig& rig,
                                         const PriorEdgeOptions& options) {
  options.Check();
  std::vector<RegistrationEdge> all;
  auto append = [&all](std::vector<RegistrationEdge> more) {
    all.insert(all.end(), more.begin(), more.end());
  };
  if (options.rig) append(RigEdges(nodes, rig, options));
  if (options.odometry) append(OdometryEdges(nodes, rig, options));
  if (options.straightness) append(StraightnessEdges(nodes, rig, options));
  return all;
}

}  // namespace sewer3d
