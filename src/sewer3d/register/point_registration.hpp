#pragma once
/// \file
/// Rigid registration of matched 3-D points with per-point covariances (the geometric core of
/// the paper's feature-based registration, §4.3): RANSAC over the minimal 3-point solver,
/// Umeyama on the inliers, then Gauss–Newton on the Mahalanobis point-to-point cost
///   E(R, t) = Σ_i r_iᵀ W_i r_i,  r_i = R b_i + t − a_i,  W_i = (C_a,i + R C_b,i Rᵀ)⁻¹,
/// with re-selection of inliers by a χ²(3) gate, and the 6×6 information of the result.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/posegraph/pose_graph.hpp"
#include "sewer3d/register/information.hpp"

namespace sewer3d {

/// Noise of a point lifted from a depth map at a keypoint. Structured-light triangulation
/// gives z = f b / d, so a disparity error σ_d becomes σ_z = z² σ_d / (f b): the depth noise
/// grows with z² and is written σ_z(z) = sigma_z_ref_mm · (z / z_ref_mm)². The keypoint's own
/// localisation error σ_px moves the point across the ray by z σ_px / f. For P = z (x, y, 1)
/// (x, y undistorted normalised coordinates):
///   C = (z σ_px / f)² diag(1, 1, 0) + σ_z² (x, y, 1)(x, y, 1)ᵀ.
struct DepthNoiseModel {
  double sigma_z_ref_mm = 0.03;  ///< depth noise at z_ref_mm
  double z_ref_mm = 150.0;
  double sigma_keypoint_px = 0.3;  ///< keypoint localisation, px

  void Check() const;
  /// Covariance (mm²) of the point z (x, y, 1) for a camera of focal length `focal_px`.
  Eigen::Matrix3d PointCovariance(const Eigen::Vector3d& p_in_camera, double focal_px) const;
};

/// A putative correspondence: the same wall point seen in a and in b (each camera frame).
struct PointMatch {
  Eigen::Vector3d a, b;
  Eigen::Matrix3d cov_a = Eigen::Matrix3d::Identity(), cov_b = Eigen::Matrix3d::Identity();
};

struct PointRegistrationOptions {
  int ransac_max_iterations = 2000;
  double ransac_confidence = 0.999;  ///< stops early once an all-inlier sample is this likely
  double ransac_threshold_mm = 1.0;  ///< inlier distance |R b + t − a| for RANSAC's scoring
  std::uint64_t seed = 1;
  int min_inliers = 12;
  int refine_iterations = 15;  ///< Gauss–Newton steps per inlier selection
  int reselect_rounds = 3;     ///< inlier re-selections by the χ² gate after refinement
  double gate_chi2 = 16.27;    ///< χ²(3) at 0.999: r ᵀ W r / s² above this is an outlier
  /// Floor of s² (PointRegistrationResult): 1 trusts the noise model at most, never more —
  /// residuals smaller than the model predicts are not taken as a licence for more confidence.
  double min_variance_factor = 1.0;
  /// Beyond this many inliers the information stops growing (it is scaled by
  /// max_effective_inliers / inliers): keypoint biases from the change of perspective between
  /// the views and depth-map interpolation shared by nearby keypoints do not average out, so
  /// thousands of matches do not give √n-times better poses (measured in
  /// docs/registration.md). 0: no cap.
  int max_effective_inliers = 400;
  /// Errors that no number of matches averages away (the module's calibration, a depth bias
  /// shared by the whole overlap) as a covariance floor added to the estimate's: σ of each
  /// translation axis (mm) and of each rotation axis (degrees). 0: none.
  double floor_translation_mm = kFloorTranslationMm;
  double floor_rotation_deg = kFloorRotationDeg;

  void Check() const;
};

struct PointRegistrationResult {
  bool converged = false;  ///< enough inliers and Gauss–Newton converged
  Rigid3d a_from_b;
  /// Information of the pose graph residual (information.hpp): D H D / s², H = Σ Jᵀ W J,
  /// times min(1, max_effective_inliers / inliers).
  Matrix6d information = Matrix6d::Zero();
  std::vector<int> inliers;  ///< indices into the matches
  double rms_mm = 0.0;       ///< RMS of |r_i| over the inliers
  /// a-posteriori variance factor s² = Σ rᵀ W r / (3 n − 6) (how far the noise model is off;
  /// 1 when it is right), floored at min_variance_factor; the information is divided by it.
  double variance_factor = 1.0;
  int ransac_inliers = 0;
  int ransac_iterations = 0;
  int iterations = 0;  ///< Gauss–Newton steps in all
};

/// Registers b onto a from `matches`. Never throws for bad data: `converged` false when fewer
/// than min_inliers survive. Throws std::invalid_argument for bad options.
PointRegistrationResult RegisterPoints(const std::vector<PointMatch>& matches,
                                       const PointRegistrationOptions& options);

}  // namespace sewer3d
