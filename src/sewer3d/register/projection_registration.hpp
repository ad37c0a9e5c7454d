#pragma once
/// \file
/// Projection-based pairwise registration (paper §4.3, for texture-poor walls such as plastic
/// pipe): b's depth-map points are associated projectively with a's surface — each point,
/// moved by the current a_from_b, is projected into a's camera and meets a's point and normal
/// there (bilinear in a's point and normal maps) — and the point-to-plane cost
///   E = Σ_i ρ(n_iᵀ (R p_i + t − q_i))
/// is minimised by Gauss–Newton from an initial guess (odometry), ρ Huber with its scale from
/// the residuals' median absolute deviation. Where colour is given, a photometric term joins
/// it (photometric.hpp): the geometry's weak directions are first searched for the textures'
/// best correlation, and where that peak is clear, the intensity residuals, weighted by their own
/// robust σ, add their rows to the same Gauss–Newton steps and their information to Ω.
///
/// The information is the Gauss–Newton Hessian divided by the residual variance,
/// Ω = D (Σ w_i J_iᵀ J_i) D / σ² (information.hpp for D and the update convention), so that
/// the directions the geometry does not constrain — translation along a cylinder's axis and
/// rotation about it — carry near-zero information. Those directions are also left where the
/// initial guess put them: each step is solved only in the span of the Hessian's eigenvectors
/// above a (small) ratio of the largest, and Ω keeps only that span (zero information in the
/// directions not estimated). Neighbouring samples share depth-map interpolation; take
/// sample_step_px at least the spacing of the measured spots, or Ω is over-confident.

#include <opencv2/core.hpp>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/register/depth_geometry.hpp"
#include "sewer3d/register/information.hpp"
#include "sewer3d/register/photometric.hpp"

namespace sewer3d {

struct ProjectionRegistrationOptions {
  int sample_step_px = 4;    ///< every n-th pixel of b (rows and columns)
  int normal_step_px = 3;    ///< central differences of a's points for its normals
  int normal_smooth_px = 5;  ///< box over a's points before the differences (NormalMap)
  /// Larger steps between neighbours: no normal, no lookup (a depth edge). Joints and steps of
  /// a few mm are what constrains the slide along a pipe, so keep them.
  double max_depth_step_mm = 5.0;
  double max_distance_mm = 5.0;  ///< association gate of the first iteration
  double min_gate_mm = 0.3;      ///< the gate shrinks to max(4 σ, this) as it converges
  double huber_k = 1.345;        ///< Huber threshold in units of the robust σ
  int max_iterations = 100;      ///< Huber IRLS converges linearly where few points constrain
  /// Done when a step's Mahalanobis length δᵀ Ω δ (in the information of the current
  /// correspondences) falls below this: the step is far inside the estimate's own uncertainty.
  double convergence_chi2 = 1e-4;
  /// Or when the step moves no point of the scene by more than this (translation, and rotation
  /// as arc at the scene's mean distance): where only a few edges constrain a direction,
  /// re-association walks it by µm per iteration long after the estimate is settled.
  double convergence_step_mm = 2e-3;
  /// Degenerate when the smallest / largest eigenvalue (rotation as arc at L) is below this.
  /// A bare cylinder gives ~1e-5 (only the normals' noise constrains its symmetries); a bump of
  /// 3 mm × 8 mm σ in a 648 × 486 view ~5e-4.
  double degeneracy_ratio = 1e-4;
  /// Steps are solved only along eigenvectors above this ratio: directions with less
  /// information stay at the initial guess instead of following the normals' noise (which
  /// otherwise walks a cylinder's slide and turn by ~0.03 mm / 0.03° per iteration).
  double freeze_ratio = 5e-5;
  /// Noise in a's normals tilts every sample's constraint a little, which reads as information
  /// in every direction, the unconstrained ones included: Σ w σ_n² (σ_n² from
  /// NormalNoiseVariance). Directions below this many times that floor are frozen and get no
  /// information; the others get their eigenvalue less the floor.
  double noise_floor_factor = 3.0;
  int min_correspondences = 100;
  /// Covariance floor (WithCovarianceFloor) over the constrained directions: depth-map errors
  /// shared by the whole overlap (calibration, the decoder's interpolation between spots) that
  /// thousands of samples do not average away.
  double floor_translation_mm = kFloorTranslationMm;
  double floor_rotation_deg = kFloorRotationDeg;
  PhotometricOptions photometric;  ///< used only where both colours are given

  void Check() const;
};

struct ProjectionRegistrationReport {
  int samples_b = 0;        ///< b's sampled points with depth
  int correspondences = 0;  ///< associated and inside the gate at the end
  int iterations = 0;
  double gate_mm = 0.0;          ///< the last association gate
  InformationSpectrum spectrum;  ///< of the information before the covariance floor, L = mean
                                 ///< distance of b's points
  /// The photometric term: whether it was used, the search's correlations (at the guess after
  /// the geometry, at its peak, best elsewhere) and shift along the weak directions (mm), the
  /// textured samples and their residual σ (intensity 0–1) at the end.
  bool photometric = false;
  int texture_overlap = 0;     ///< TextureSearchResult::overlap
  bool texture_ridge = false;  ///< TextureSearchResult::ridge
  /// The search found a clear peak but the steps with the texture did not converge: the
  /// result is the geometry's alone.
  bool texture_diverged = false;
  double ncc_start = 0.0, ncc_peak = 0.0, ncc_other = 0.0;
  Eigen::Vector2d search_shift_mm = Eigen::Vector2d::Zero();
  int texture_samples = 0;
  double sigma_intensity = 0.0;
};

struct ProjectionRegistrationResult {
  bool converged = false;  ///< the step fell below convergence_chi2 with enough correspondences
  Rigid3d a_from_b;
  /// Information of the pose-graph residual [translation; 2 vec(rotation error)] (mm, rad).
  Matrix6d information = Matrix6d::Zero();
  int correspondences = 0;
  double rms_mm = 0.0;      ///< point-to-plane residual RMS of the correspondences
  double sigma_mm = 0.0;    ///< residual noise σ used to scale the information
  bool degenerate = false;  ///< report.spectrum.degenerate
  Vector6d weak_direction = Vector6d::Zero();  ///< report.spectrum.weak_direction
  ProjectionRegistrationReport report;
};

/// Registers b's depth map onto a's from `initial_a_from_b`; then, where both colour images are
/// given (not empty), options.photometric.enabled and the geometry converged, the photometric
/// term joins (when its search finds a clear peak) and the pose is solved again with both; if
/// that does not converge the geometry's result stands (report.texture_diverged). Expected failures
/// (too few correspondences, no convergence) give converged = false; throws
/// std::invalid_argument for bad options or maps whose sizes differ from their cameras.
ProjectionRegistrationResult RegisterProjection(const RgbdImage& a, const CameraModel& camera_a,
                                                const RgbdImage& b, const CameraModel& camera_b,
                                                const Rigid3d& initial_a_from_b,
                                                const ProjectionRegistrationOptions& options);
/// The geometry alone (no colour).
ProjectionRegistrationResult RegisterProjection(const cv::Mat1f& depth_a,
                                                const CameraModel& camera_a,
                                                const cv::Mat1f& depth_b,
                                                const CameraModel& camera_b,
                                                const Rigid3d& initial_a_from_b,
                                                const ProjectionRegistrationOptions& options);

}  // namespace sewer3d
