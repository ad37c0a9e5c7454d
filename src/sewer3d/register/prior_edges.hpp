#pragma once
/// \file
/// Evidence beyond the pairwise registrations (issue 15 item 5): the rigid carrier between the
/// modules of one instant (rig edges), the cable counter between consecutive acquisitions of a
/// module (odometry edges), and the paper's straightness regularisation between the first and
/// the last acquisition of each module. Each is a relative camera pose predicted by the rig
/// (carrier_from_camera) and the odometry distance, with a covariance built in the carrier frame
/// and carried into the first camera's frame in the pose graph's residual order
/// (information.hpp).
///
/// Relative pose of two cameras: camera_a_from_camera_b = C_a⁻¹ · M · C_b, with C the rig's
/// carrier_from_camera and M = carrier(t_a)_from_carrier(t_b) = translation (0, 0, d_b − d_a)
/// (the carrier moves along its axis by the odometry distance between the two times). An error
/// (δt, δθ) of M in the carrier frame (t ← t + δt, R ← Exp(δθ) R) moves the residual by
/// J = [[R_aᵀ, −R_aᵀ [M_R p_b]×], [0, R_aᵀ]] with R_a = C_a's rotation and p_b = C_b's
/// translation: rotating the carrier swings camera b about the carrier centre. The covariance
/// of that camera-frame error becomes the residual order by D · D (information.hpp).

#include <string>
#include <vector>

#include "sewer3d/register/information.hpp"
#include "sewer3d/register/initial_poses.hpp"
#include "sewer3d/run/rig.hpp"

namespace sewer3d {

/// Where an edge of the registration graph comes from.
enum class RegistrationEdgeType { kFeature, kProjection, kRig, kOdometry, kStraightness };
inline constexpr int kRegistrationEdgeTypes = 5;

/// "feature", "projection", "rig", "odometry", "straightness".
const char* RegistrationEdgeTypeName(RegistrationEdgeType type);
/// Feature and projection edges: measured by registration, robust loss and χ² gate apply.
bool IsPairwiseEdge(RegistrationEdgeType type);

/// One edge between two nodes (indices into the nodes).
struct RegistrationEdge {
  int a = 0, b = 0;
  RegistrationEdgeType type = RegistrationEdgeType::kRig;
  Rigid3d a_from_b;  ///< measured or predicted pose of camera b in camera a's frame
  /// Information of the pose-graph residual (translation mm, rotation rad), SPD.
  Matrix6d information = Matrix6d::Identity();
  int inliers = 0;      ///< pairwise edges: inlier matches or correspondences
  double rms_mm = 0.0;  ///< pairwise edges: residual RMS of the registration
};

struct PriorEdgeOptions {
  bool rig = true, odometry = true, straightness = true;
  /// Rig calibration: uncertainty of a camera's pose on the carrier (each of the two).
  double rig_sigma_mm = 0.05;
  double rig_sigma_deg = 0.01;
  /// Cable counter: reading noise (each reading) and scale error (fraction of the distance).
  double odometry_noise_mm = 0.5;
  double odometry_scale_sigma = 0.005;
  /// Carrier motion the odometry does not see, as rates: lateral wander and turning (pitch,
  /// yaw, roll) per second between the two times of a rig edge (the odd modules fire later).
  double lateral_speed_mm_s = 5.0;
  double turn_rate_deg_s = 3.0;
  /// Odometry edges are weak across the pipe: what the carrier may wander and turn between two
  /// acquisitions of a module.
  double odometry_lateral_sigma_mm = 5.0;
  double odometry_rotation_sigma_deg = 2.0;
  /// Straightness: the gentlest bend the pipe may have (σ of the regularisation, see
  /// StraightnessCovariance), plus the carrier's wander, wobble and roll inside the pipe.
  double min_bend_radius_mm = 30000.0;
  double carrier_wander_mm = 2.0;
  double carrier_wobble_deg = 0.3;
  double carrier_roll_deg = 5.0;

  void Check() const;
};

/// The covariance (residual order, camera a's frame) of C_a⁻¹ · M · C_b for an error of M with
/// covariance `covariance_in_carrier` (carrier frame, (δt mm, δθ rad)); see the file comment.
Matrix6d CameraCovarianceFromCarrier(const Rigid3d& carrier_from_camera_a,
                                     const Rigid3d& carrier_a_from_carrier_b,
                                     const Rigid3d& carrier_from_camera_b,
                                     const Matrix6d& covariance_in_carrier);

/// Covariance of the straight-pipe prediction over a carrier travel of `length_mm`, carrier
/// frame: a bend of radius R puts the end L²/(2R) aside of the start's axis and turns it by
/// L/R (pitch and yaw); those are the σ at R = min_bend_radius_mm, combined with the carrier's
/// wander (√2 · wander, both ends) and wobble. Along the axis and about it (roll) it says
/// nearly nothing: σ = L + 10 mm and carrier_roll_deg (the odometry edges carry the distance).
Matrix6d StraightnessCovariance(double length_mm, const PriorEdgeOptions& options);

/// Rig edges: for every counter, between the modules of that instant in the rig's cyclic
/// order (a chain: module k to the next present one). Throws std::invalid_argument for bad
/// options or a node whose module the rig lacks.
std::vector<RegistrationEdge> RigEdges(const std::vector<AcquisitionNode>& nodes, const Rig& rig,
                                       const PriorEdgeOptions& options);

/// Odometry edges between consecutive acquisitions (by counter) of each module. A node in an
/// odometry gap adds its distance_sigma_mm along the axis (and a rig edge its speed_sigma_mm_s
/// times the two cameras' time difference).
std::vector<RegistrationEdge> OdometryEdges(const std::vector<AcquisitionNode>& nodes,
                                            const Rig& rig, const PriorEdgeOptions& options);

/// Straightness edges from the first to the last acquisition of each module (when they
/// differ), predicting a straight pipe with StraightnessCovariance.
std::vector<RegistrationEdge> StraightnessEdges(const std::vector<AcquisitionNode>& nodes,
                                                const Rig& rig, const PriorEdgeOptions& options);

/// All three kinds the options enable, in that order.
std::vector<RegistrationEdge> PriorEdges(const std::vector<AcquisitionNode>& nodes, const Rig& rig,
                                         const PriorEdgeOptions& options);

}  // namespace sewer3d
