#include "sewer3d/register/projection_registration.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "sewer3d/core/check.hpp"
#include "sewer3d/register/depth_geometry.hpp"

namespace sewer3d {
namespace {

using Association = ResidualRow;  // ∂r/∂δ and the point-to-plane residual, mm

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

// The normal equations of a term divided by its residual variance, so that terms add.
Normal Weighted(Normal n, double sigma) {
  const double w = 1.0 / (sigma * sigma);
  n.h *= w;
  n.g *= w;
  n.noise_floor *= w;
  return n;
}

Normal Sum(Normal a, const Normal& b) {
  a.h += b.h;
  a.g += b.g;
  a.noise_floor += b.noise_floor;
  return a;
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

// The texture term's data: a's fine texture with gradients, b's samples on it, and the
// direction its correlation left open (a ridge; unit, (mm, L·rad) metric) if any.
struct TextureTerm {
  TextureMaps a;
  std::vector<TextureSample> b;
  std::optional<Vector6d> ridge;
};

// The normal equations with nothing along `v` (unit, (mm, L·rad) metric): projected onto the
// complement of v in the scaled metric, so that v gets neither steps nor information.
Normal WithoutDirection(Normal n, const Vector6d& v, double length_mm) {
  Vector6d scale;
  scale << 1, 1, 1, 1 / length_mm, 1 / length_mm, 1 / length_mm;
  const Matrix6d p = Matrix6d::Identity() - v * v.transpose();
  const Matrix6d hs = p * (scale.asDiagonal() * n.h * scale.asDiagonal()) * p;
  const Vector6d gs = p * scale.cwiseProduct(n.g);
  const Vector6d inv = scale.cwiseInverse();
  n.h = inv.asDiagonal() * hs * inv.asDiagonal();
  n.g = inv.cwiseProduct(gs);
  return n;
}

// What one registration works on: a's surface and b's points, and the texture where used.
struct Problem {
  SurfaceA a;
  std::vector<Eigen::Vector3d> b;
  double length_mm = 1.0;  ///< mean distance of b's points
  std::optional<TextureTerm> texture;
};

// The associations at a pose and the normal equations of both terms, each divided by its
// residual variance (robust σ in the loop, the weighted mean square at the end: `final`).
struct Equations {
  std::vector<Association> geometric;
  PhotometricRows photometric;
  Normal n;
  double sigma_mm = 0.0, sigma_intensity = 0.0;
};

double FinalSigma(const Normal& n) {
  return std::sqrt(n.weighted_r2 / std::max(1.0, n.weights - 6.0));
}

Equations Equate(const Problem& p, const Rigid3d& pose, double gate,
                 const ProjectionRegistrationOptions& o, bool final) {
  Equations e;
  e.geometric = Associate(p.a, p.b, pose, gate);
  if (static_cast<int>(e.geometric.size()) < o.min_correspondences) return e;
  const double robust = std::max(RobustSigma(e.geometric), 1e-6);
  const Normal geometric = Accumulate(e.geometric, o.huber_k * robust, p.a.normal_variance);
  e.sigma_mm = final ? FinalSigma(geometric) : robust;
  e.n = Weighted(geometric, std::max(e.sigma_mm, 1e-6));
  if (!p.texture) return e;
  e.photometric = AssociatePhotometric(p.texture->a, p.a.camera, p.texture->b, pose);
  if (static_cast<int>(e.photometric.rows.size()) < o.photometric.min_samples) return e;
  const double robust_i = std::max(RobustSigma(e.photometric.rows), 1e-9);
  Normal texture = Accumulate(e.photometric.rows, o.huber_k * robust_i, 0.0);
  // Along its ridge the textures' correlation did not say where b lies: no steps, no information.
  if (p.texture->ridge) texture = WithoutDirection(texture, *p.texture->ridge, p.length_mm);
  e.sigma_intensity = final ? FinalSigma(texture) : robust_i;
  e.n = Sum(e.n, Weighted(texture, std::max(e.sigma_intensity, 1e-9)));
  return e;
}

struct Solve {
  Rigid3d pose;
  double gate = 0.0;
  int iterations = 0;
  bool converged = false;
  bool too_few = false;  ///< stopped: fewer correspondences than min_correspondences
  Normal last;           ///< the normal equations of the last step
};

// Gauss–Newton from `s.pose` until a step is negligible (at most max_iterations steps).
void Iterate(const Problem& p, const ProjectionRegistrationOptions& o, Solve& s) {
  s.converged = false;
  for (int it = 0; it < o.max_iterations && !s.converged; ++it) {
    const Equations e = Equate(p, s.pose, s.gate, o, false);
    ++s.iterations;
    if (static_cast<int>(e.geometric.size()) < o.min_correspondences) {
      s.too_few = true;
      return;
    }
    const Vector6d delta = ObservableStep(e.n, Observable(e.n, p.length_mm, o));
    s.pose = ApplyUpdate(s.pose, delta);
    s.last = e.n;
    const double step_mm = std::max(delta.head<3>().norm(), delta.tail<3>().norm() * p.length_mm);
    s.converged = delta.dot(e.n.h * delta) < o.convergence_chi2 || step_mm < o.convergence_step_mm;
    s.gate = std::clamp(4.0 * e.sigma_mm, o.min_gate_mm, o.max_distance_mm);
  }
}

// The directions the geometry leaves unconstrained (frozen), weakest first, as updates δ per
// mm of the (mm, L·rad) metric; at most photometric.max_search_directions.
std::vector<Vector6d> WeakDirections(const Normal& n, double length_mm,
                                     const ProjectionRegistrationOptions& o) {
  const ObservableSpace space = Observable(n, length_mm, o);
  std::vector<Vector6d> out;
  for (int i = 0; i < 6 && static_cast<int>(out.size()) < o.photometric.max_search_directions;
       ++i) {
    if (!space.kept[i]) out.push_back(space.scale.cwiseProduct(space.eig.eigenvectors().col(i)));
  }
  return out;
}

// Searches the geometry's weak directions for the textures' correlation peak; the texture term
// joins the problem when the peak is clear (or, with no weak direction, when the textures
// already correlate at the geometry's pose).
void JoinTexture(const RgbdImage& a, const CameraModel& camera_a, const RgbdImage& b,
                 const CameraModel& camera_b, const ProjectionRegistrationOptions& o, Problem& p,
                 Solve& s, ProjectionRegistrationReport& report) {
  const PhotometricOptions& po = o.photometric;
  const CameraIntrinsics& in = camera_a.intrinsics();
  const double mm_per_px = p.length_mm / std::sqrt(in.fx * in.fy);
  const double coarse_px = std::max(po.blur_px, 0.5 * po.search_step_mm / mm_per_px);
  const double highpass_px = po.highpass_mm / mm_per_px;
  const GreyTexture grey_a = MakeGreyTexture(a.color_bgr, highpass_px);
  const GreyTexture grey_b = MakeGreyTexture(b.color_bgr, highpass_px);
  TextureTerm fine{MakeTextureMaps(grey_a, po.blur_px), {}, std::nullopt};
  fine.b = SampleTexture(p.b, camera_b, TextureIntensity(grey_b, po.blur_px));
  const cv::Mat1f coarse_a = TextureIntensity(grey_a, coarse_px);
  const std::vector<TextureSample> coarse_b =
      SampleTexture(SampleDepthPoints(b.depth, camera_b, po.search_sample_step_px), camera_b,
                    TextureIntensity(grey_b, coarse_px));
  const std::vector<Vector6d> weak = WeakDirections(s.last, p.length_mm, o);
  const TextureSearchResult found =
      SearchTexture({coarse_a, coarse_b, fine.a.intensity, fine.b}, camera_a, s.pose, weak, po);
  report.texture_overlap = found.overlap;
  report.texture_ridge = found.ridge;
  report.ncc_start = found.ncc_start;
  report.ncc_peak = found.ncc_peak;
  report.ncc_other = found.ncc_other;
  report.search_shift_mm = found.shift_mm;
  report.photometric = weak.empty() ? found.ncc_start >= po.min_ncc : found.clear;
  if (!report.photometric) return;
  s.pose = found.pose;
  if (found.ridge) {
    Vector6d v = found.along_ridge;
    v.tail<3>() *= p.length_mm;  // δ per mm → unit vector of the (mm, L·rad) metric
    fine.ridge = v.normalized();
  }
  p.texture = std::move(fine);
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
  CheckWithin("photometric.", [&] { photometric.Check(); });
}

ProjectionRegistrationResult RegisterProjection(const RgbdImage& a, const CameraModel& camera_a,
                                                const RgbdImage& b, const CameraModel& camera_b,
                                                const Rigid3d& initial_a_from_b,
                                                const ProjectionRegistrationOptions& options) {
  options.Check();
  Problem p{{camera_a, PointMap(a.depth, camera_a), {}, options.max_depth_step_mm}, {}, 1.0, {}};
  p.a.normals = NormalMap(p.a.points, options.normal_step_px, options.normal_smooth_px,
                          options.max_depth_step_mm);
  // Normals this far apart share no pixel of their boxes and differences.
  p.a.normal_variance =
      NormalNoiseVariance(p.a.normals, 2 * options.normal_step_px + options.normal_smooth_px);
  SEWER3D_VALIDATE(
      b.depth.cols == camera_b.intrinsics().width && b.depth.rows == camera_b.intrinsics().height,
      "depth_b", "is not the camera's size");
  const bool colour = !a.color_bgr.empty() && !b.color_bgr.empty();
  SEWER3D_VALIDATE(
      !colour || (a.color_bgr.size() == a.depth.size() && b.color_bgr.size() == b.depth.size()),
      "color_bgr", "must be the depth map's size");
  p.b = SampleDepthPoints(b.depth, camera_b, options.sample_step_px);
  ProjectionRegistrationResult out;
  out.report.samples_b = static_cast<int>(p.b.size());
  if (!p.b.empty()) {
    double sum = 0.0;
    for (const Eigen::Vector3d& x : p.b) sum += x.norm();
    p.length_mm = sum / static_cast<double>(p.b.size());
  }

  Solve s;
  s.pose = initial_a_from_b;
  s.gate = options.max_distance_mm;
  Iterate(p, options, s);
  if (s.converged && colour && options.photometric.enabled) {
    const Solve geometric = s;
    JoinTexture(a, camera_a, b, camera_b, options, p, s, out.report);
    if (p.texture) Iterate(p, options, s);
    if (p.texture && !s.converged) {  // the geometry's own result stands
      s = geometric;
      p.texture.reset();
      out.report.photometric = false;
      out.report.texture_diverged = true;
    }
  }
  out.report.iterations = s.iterations;
  out.report.gate_mm = s.gate;
  const Equations e = Equate(p, s.pose, s.gate, options, true);
  out.correspondences = out.report.correspondences = static_cast<int>(e.geometric.size());
  if (s.too_few || out.correspondences < options.min_correspondences) return out;
  out.report.texture_samples = static_cast<int>(e.photometric.rows.size());
  out.report.sigma_intensity = e.sigma_intensity;
  out.sigma_mm = e.sigma_mm;
  double r2 = 0.0;
  for (const Association& x : e.geometric) r2 += x.r * x.r;
  out.rms_mm = std::sqrt(r2 / static_cast<double>(e.geometric.size()));
  out.a_from_b = s.pose;
  const Matrix6d measured =
      ToResidualOrder(ObservableInformation(Observable(e.n, p.length_mm, options)));
  // Degeneracy is the data's: judged before the floor, which caps every direction alike.
  out.report.spectrum = AnalyseInformation(measured, p.length_mm, options.degeneracy_ratio);
  out.information =
      WithCovarianceFloor(measured, options.floor_translation_mm, options.floor_rotation_deg);
  out.degenerate = out.report.spectrum.degenerate;
  out.weak_direction = out.report.spectrum.weak_direction;
  out.converged = s.converged;
  return out;
}

ProjectionRegistrationResult RegisterProjection(const cv::Mat1f& depth_a,
                                                const CameraModel& camera_a,
                                                const cv::Mat1f& depth_b,
                                                const CameraModel& camera_b,
                                                const Rigid3d& initial_a_from_b,
                                                const ProjectionRegistrationOptions& options) {
  return RegisterProjection(RgbdImage{{}, depth_a}, camera_a, RgbdImage{{}, depth_b}, camera_b,
                            initial_a_from_b, options);
}

}  // namespace sewer3d
