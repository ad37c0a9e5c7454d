#include "sewer3d/register/projection_registration.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "sewer3d/core/check.hpp"
#include "sewer3d/register/depth_geometry.hpp"

namespace sewer3d {
namespace {

struct Association {
  Eigen::Matrix<double, 1, 6> j;  ///< ∂r/∂δ
  double r = 0.0;                 ///< point-to-plane residual, mm
};

struct SurfaceA {
  const CameraModel& camera;
  cv::Mat3f points, normals;
  double max_spread_mm;
  double normal_variance = 0.0;  ///< NormalNoiseVariance of `normals`, rad²
};

// Projective association of every sample of b at the pose; residuals beyond the gate dropped.
std::vector<Association> Associate(const SurfaceA& a, const std::vector<Eigen::Vector3d>& b,
                                   const Rigid3d& pose, double gate_mm) {
  std::vector<Association> out;
  const Eigen::Matrix3d r = pose.RotationMatrix();
  for (const Eigen::Vector3d& p_b : b) {
    const Eigen::Vector3d x = r * p_b;
    const Eigen::Vector3d p = x + pose.translation;
    const auto px = a.camera.Project(p);
    if (!px) continue;
    const auto q = SampleBilinear(a.points, *px, a.max_spread_mm);
    if (!q) continue;
    const auto n_raw = SampleBilinear(a.normals, *px, 0.5);
    if (!n_raw || !(n_raw->norm() > 0.5)) continue;
    const Eigen::Vector3d n = n_raw->normalized();
    Association s;
    s.r = n.dot(p - *q);
    if (std::abs(s.r) > gate_mm) continue;
    s.j << n.transpose(), x.cross(n).transpose();  // n·(δt + δθ × x)
    out.push_back(s);
  }
  return out;
}

double RobustSigma(const std::vector<Association>& s) {
  std::vector<double> a;
  a.reserve(s.size());
  for (const Association& x : s) a.push_back(std::abs(x.r));
  if (a.empty()) return 0.0;
  std::nth_element(a.begin(), a.begin() + a.size() / 2, a.end());
  return 1.4826 * a[a.size() / 2];
}

struct Normal {
  Matrix6d h = Matrix6d::Zero();
  Vector6d g = Vector6d::Zero();
  double weighted_r2 = 0.0, weights = 0.0, r2 = 0.0;
  /// What the normals' noise alone puts into every direction of h (scaled metric): Σ w σ_n².
  double noise_floor = 0.0;
};

Normal Accumulate(const std::vector<Association>& s, double huber_mm, double normal_variance) {
  Normal n;
  for (const Association& x : s) {
    const double w = std::abs(x.r) <= huber_mm ? 1.0 : huber_mm / std::abs(x.r);
    n.h += w * x.j.transpose() * x.j;
    n.g += w * x.j.transpose() * x.r;
    n.weighted_r2 += w * x.r * x.r;
    n.weights += w;
    n.r2 += x.r * x.r;
  }
  n.noise_floor = n.weights * normal_variance;
  return n;
}

// The eigen-decomposition of S H S (S as information.hpp) and which eigenvectors the data
// constrain: above ratio · λ_max and clearly above the normals' noise floor.
struct ObservableSpace {
  Vector6d scale;
  Eigen::SelfAdjointEigenSolver<Matrix6d> eig;
  std::array<bool, 6> kept{};
  double floor = 0.0;
};

ObservableSpace Observable(const Normal& n, double length_mm,
                           const ProjectionRegistrationOptions& o) {
  ObservableSpace out;
  out.scale << 1, 1, 1, 1 / length_mm, 1 / length_mm, 1 / length_mm;
  const Matrix6d hs = out.scale.asDiagonal() * n.h * out.scale.asDiagonal();
  out.eig.compute(0.5 * (hs + hs.transpose()));
  out.floor = n.noise_floor;
  const double threshold =
      std::max(o.freeze_ratio * out.eig.eigenvalues()(5), o.noise_floor_factor * out.floor);
  for (int i = 0; i < 6; ++i) {
    const double lambda = out.eig.eigenvalues()(i);
    out.kept[i] = lambda > threshold && lambda > 0.0;
  }
  return out;
}

// −H⁻¹ g restricted to the constrained eigenvectors.
Vector6d ObservableStep(const Normal& n, const ObservableSpace& o) {
  const Vector6d gs = o.scale.cwiseProduct(n.g);
  Vector6d step_s = Vector6d::Zero();
  for (int i = 0; i < 6; ++i) {
    if (!o.kept[i]) continue;
    const Vector6d v = o.eig.eigenvectors().col(i);
    step_s -= (v.dot(gs) / o.eig.eigenvalues()(i)) * v;
  }
  return o.scale.cwiseProduct(step_s);
}

// H over the same eigenvectors, each less the noise floor (the part of its eigenvalue the
// normals' noise alone would give); what the step did not estimate carries no information.
Matrix6d ObservableInformation(const ObservableSpace& o) {
  Matrix6d kept = Matrix6d::Zero();
  for (int i = 0; i < 6; ++i) {
    if (!o.kept[i]) continue;
    const Vector6d v = o.eig.eigenvectors().col(i);
    kept += (o.eig.eigenvalues()(i) - o.floor) * v * v.transpose();
  }
  const Vector6d inv = o.scale.cwiseInverse();
  return inv.asDiagonal() * kept * inv.asDiagonal();
}

}  // namespace

void ProjectionRegistrationOptions::Check() const {
  SEWER3D_VALIDATE(sample_step_px >= 1, "sample_step_px", "must be >= 1, got " << sample_step_px);
  SEWER3D_VALIDATE(normal_step_px >= 1, "normal_step_px", "must be >= 1, got " << normal_step_px);
  SEWER3D_VALIDATE(normal_smooth_px >= 1, "normal_smooth_px",
                   "must be >= 1, got " << normal_smooth_px);
  ValidatePositive("noise_floor_factor", noise_floor_factor);
  ValidateNotNegative("floor_translation_mm", floor_translation_mm);
  ValidateNotNegative("floor_rotation_deg", floor_rotation_deg);
  SEWER3D_VALIDATE(freeze_ratio >= 0.0 && freeze_ratio < 1.0, "freeze_ratio",
                   "must lie in [0, 1), got " << freeze_ratio);
  ValidatePositive("max_depth_step_mm", max_depth_step_mm);
  ValidatePositive("max_distance_mm", max_distance_mm);
  ValidatePositive("min_gate_mm", min_gate_mm);
  ValidatePositive("huber_k", huber_k);
  SEWER3D_VALIDATE(max_iterations >= 1, "max_iterations", "must be >= 1");
  ValidatePositive("convergence_chi2", convergence_chi2);
  ValidatePositive("convergence_step_mm", convergence_step_mm);
  SEWER3D_VALIDATE(degeneracy_ratio > 0.0 && degeneracy_ratio < 1.0, "degeneracy_ratio",
                   "must lie in (0, 1), got " << degeneracy_ratio);
  SEWER3D_VALIDATE(min_correspondences >= 6, "min_correspondences", "must be >= 6");
}

ProjectionRegistrationResult RegisterProjection(const cv::Mat1f& depth_a,
                                                const CameraModel& camera_a,
                                                const cv::Mat1f& depth_b,
                                                const CameraModel& camera_b,
                                                const Rigid3d& initial_a_from_b,
                                                const ProjectionRegistrationOptions& options) {
  options.Check();
  SurfaceA a{camera_a, PointMap(depth_a, camera_a), {}, options.max_depth_step_mm};
  a.normals = NormalMap(a.points, options.normal_step_px, options.normal_smooth_px,
                        options.max_depth_step_mm);
  // Normals this far apart share no pixel of their boxes and differences.
  a.normal_variance =
      NormalNoiseVariance(a.normals, 2 * options.normal_step_px + options.normal_smooth_px);
  SEWER3D_VALIDATE(
      depth_b.cols == camera_b.intrinsics().width && depth_b.rows == camera_b.intrinsics().height,
      "depth_b", "is not the camera's size");
  const std::vector<Eigen::Vector3d> b =
      SampleDepthPoints(depth_b, camera_b, options.sample_step_px);
  ProjectionRegistrationResult out;
  out.report.samples_b = static_cast<int>(b.size());
  double length_mm = 0.0;
  for (const Eigen::Vector3d& p : b) length_mm += p.norm();
  length_mm = b.empty() ? 1.0 : length_mm / static_cast<double>(b.size());

  Rigid3d pose = initial_a_from_b;
  double gate = options.max_distance_mm;
  std::vector<Association> s;
  bool converged = false;
  for (int it = 0; it < options.max_iterations && !converged; ++it) {
    s = Associate(a, b, pose, gate);
    out.report.iterations = it + 1;
    if (static_cast<int>(s.size()) < options.min_correspondences) {
      out.correspondences = out.report.correspondences = static_cast<int>(s.size());
      out.report.gate_mm = gate;
      return out;
    }
    const double sigma = std::max(RobustSigma(s), 1e-6);
    const Normal n = Accumulate(s, options.huber_k * sigma, a.normal_variance);
    const Vector6d delta = ObservableStep(n, Observable(n, length_mm, options));
    pose = ApplyUpdate(pose, delta);
    const double step_mm = std::max(delta.head<3>().norm(), delta.tail<3>().norm() * length_mm);
    converged = delta.dot(n.h * delta) / (sigma * sigma) < options.convergence_chi2 ||
                step_mm < options.convergence_step_mm;
    gate = std::clamp(4.0 * sigma, options.min_gate_mm, options.max_distance_mm);
  }
  s = Associate(a, b, pose, gate);
  out.report.gate_mm = gate;
  out.correspondences = out.report.correspondences = static_cast<int>(s.size());
  if (out.correspondences < options.min_correspondences) return out;
  const double sigma = std::max(RobustSigma(s), 1e-6);
  const Normal n = Accumulate(s, options.huber_k * sigma, a.normal_variance);
  // σ² of the residuals as the Huber-weighted mean square, 6 parameters estimated.
  out.sigma_mm = std::sqrt(n.weighted_r2 / std::max(1.0, n.weights - 6.0));
  out.rms_mm = std::sqrt(n.r2 / static_cast<double>(s.size()));
  out.a_from_b = pose;
  const Matrix6d measured =
      ToResidualOrder(ObservableInformation(Observable(n, length_mm, options)) /
                      std::max(out.sigma_mm * out.sigma_mm, 1e-12));
  // Degeneracy is the geometry's: judged before the floor, which caps every direction alike.
  out.report.spectrum = AnalyseInformation(measured, length_mm, options.degeneracy_ratio);
  out.information =
      WithCovarianceFloor(measured, options.floor_translation_mm, options.floor_rotation_deg);
  out.degenerate = out.report.spectrum.degenerate;
  out.weak_direction = out.report.spectrum.weak_direction;
  out.converged = converged;
  return out;
}

}  // namespace sewer3d
