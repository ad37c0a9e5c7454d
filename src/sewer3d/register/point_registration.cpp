#include "sewer3d/register/point_registration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/register/information.hpp"
#include "sewer3d/register/rigid_fit.hpp"

namespace sewer3d {
namespace {

struct Normal {
  Matrix6d h = Matrix6d::Zero();
  Vector6d g = Vector6d::Zero();
  double chi2 = 0.0;
};

Eigen::Matrix3d Weight(const PointMatch& m, const Eigen::Matrix3d& r) {
  return (m.cov_a + r * m.cov_b * r.transpose()).inverse();
}

Normal Accumulate(const std::vector<PointMatch>& matches, const std::vector<int>& use,
                  const Rigid3d& pose) {
  Normal n;
  const Eigen::Matrix3d r = pose.RotationMatrix();
  for (int i : use) {
    const PointMatch& m = matches[i];
    const Eigen::Vector3d rb = r * m.b;
    const Eigen::Vector3d res = rb + pose.translation - m.a;
    const Eigen::Matrix3d w = Weight(m, r);
    Eigen::Matrix<double, 3, 6> j;
    j << Eigen::Matrix3d::Identity(), -Skew(rb);
    n.h += j.transpose() * w * j;
    n.g += j.transpose() * w * res;
    n.chi2 += res.dot(w * res);
  }
  return n;
}

// RANSAC over the 3-point solver; returns the best inlier set (distance threshold).
std::vector<int> Ransac(const std::vector<PointMatch>& matches, const PointRegistrationOptions& o,
                        int* iterations) {
  const int n = static_cast<int>(matches.size());
  std::mt19937_64 rng(o.seed);
  std::uniform_int_distribution<int> pick(0, n - 1);
  std::vector<int> best;
  int needed = o.ransac_max_iterations;
  for (*iterations = 0; *iterations < needed; ++*iterations) {
    int s[3] = {pick(rng), pick(rng), pick(rng)};
    if (s[0] == s[1] || s[0] == s[2] || s[1] == s[2]) continue;
    const Eigen::Vector3d src[3] = {matches[s[0]].b, matches[s[1]].b, matches[s[2]].b};
    const Eigen::Vector3d dst[3] = {matches[s[0]].a, matches[s[1]].a, matches[s[2]].a};
    const auto pose = RigidFromThreePoints(src, dst, 1e-3);
    if (!pose) continue;
    std::vector<int> in;
    for (int i = 0; i < n; ++i)
      if ((*pose * matches[i].b - matches[i].a).norm() < o.ransac_threshold_mm) in.push_back(i);
    if (in.size() <= best.size()) continue;
    best = std::move(in);
    const double w = static_cast<double>(best.size()) / n;
    const double p_fail = 1.0 - w * w * w;
    if (p_fail <= 0.0) break;
    needed = std::min(
        o.ransac_max_iterations,
        static_cast<int>(std::ceil(std::log(1.0 - o.ransac_confidence) / std::log(p_fail))));
  }
  return best;
}

}  // namespace

void DepthNoiseModel::Check() const {
  ValidatePositive("sigma_z_ref_mm", sigma_z_ref_mm);
  ValidatePositive("z_ref_mm", z_ref_mm);
  ValidatePositive("sigma_keypoint_px", sigma_keypoint_px);
}

Eigen::Matrix3d DepthNoiseModel::PointCovariance(const Eigen::Vector3d& p, double focal_px) const {
  const double z = p.z();
  const double lateral = z * sigma_keypoint_px / focal_px;
  const double sigma_z = sigma_z_ref_mm * (z / z_ref_mm) * (z / z_ref_mm);
  const Eigen::Vector3d ray = p / z;  // (x, y, 1)
  Eigen::Matrix3d c = sigma_z * sigma_z * ray * ray.transpose();
  c(0, 0) += lateral * lateral;
  c(1, 1) += lateral * lateral;
  return c;
}

void PointRegistrationOptions::Check() const {
  SEWER3D_VALIDATE(ransac_max_iterations >= 1, "ransac_max_iterations", "must be >= 1");
  SEWER3D_VALIDATE(ransac_confidence > 0.0 && ransac_confidence < 1.0, "ransac_confidence",
                   "must lie in (0, 1), got " << ransac_confidence);
  ValidatePositive("ransac_threshold_mm", ransac_threshold_mm);
  SEWER3D_VALIDATE(min_inliers >= 3, "min_inliers", "must be >= 3, got " << min_inliers);
  SEWER3D_VALIDATE(refine_iterations >= 1, "refine_iterations", "must be >= 1");
  SEWER3D_VALIDATE(reselect_rounds >= 0, "reselect_rounds", "must be >= 0");
  ValidatePositive("gate_chi2", gate_chi2);
  ValidatePositive("min_variance_factor", min_variance_factor);
  ValidateNotNegative("max_effective_inliers", max_effective_inliers);
  ValidateNotNegative("floor_translation_mm", floor_translation_mm);
  ValidateNotNegative("floor_rotation_deg", floor_rotation_deg);
}

PointRegistrationResult RegisterPoints(const std::vector<PointMatch>& matches,
                                       const PointRegistrationOptions& options) {
  options.Check();
  PointRegistrationResult out;
  if (static_cast<int>(matches.size()) < options.min_inliers) return out;
  out.inliers = Ransac(matches, options, &out.ransac_iterations);
  out.ransac_inliers = static_cast<int>(out.inliers.size());
  if (out.ransac_inliers < options.min_inliers) return out;
  std::vector<Eigen::Vector3d> src, dst;
  for (int i : out.inliers) src.push_back(matches[i].b), dst.push_back(matches[i].a);
  const auto initial = UmeyamaFit(src, dst);
  if (!initial) return out;
  Rigid3d pose = *initial;
  bool converged = false;
  Normal n;
  for (int round = 0; round <= options.reselect_rounds; ++round) {
    converged = false;
    for (int it = 0; it < options.refine_iterations && !converged; ++it, ++out.iterations) {
      n = Accumulate(matches, out.inliers, pose);
      const Vector6d delta = -n.h.ldlt().solve(n.g);
      if (!delta.allFinite()) return out;
      pose = ApplyUpdate(pose, delta);
      converged = delta.head<3>().norm() < 1e-7 && delta.tail<3>().norm() < 1e-9;
    }
    n = Accumulate(matches, out.inliers, pose);
    const int dof = 3 * static_cast<int>(out.inliers.size()) - 6;
    out.variance_factor = std::max(options.min_variance_factor, n.chi2 / std::max(1, dof));
    if (round == options.reselect_rounds) break;
    // Re-select among all matches with the refined pose and the estimated noise level.
    std::vector<int> in;
    const Eigen::Matrix3d r = pose.RotationMatrix();
    for (int i = 0; i < static_cast<int>(matches.size()); ++i) {
      const Eigen::Vector3d res = r * matches[i].b + pose.translation - matches[i].a;
      if (res.dot(Weight(matches[i], r) * res) / out.variance_factor < options.gate_chi2)
        in.push_back(i);
    }
    if (static_cast<int>(in.size()) < options.min_inliers) return out;
    if (in == out.inliers) break;
    out.inliers = std::move(in);
  }
  double sum2 = 0.0;
  for (int i : out.inliers) sum2 += (pose * matches[i].b - matches[i].a).squaredNorm();
  out.rms_mm = std::sqrt(sum2 / static_cast<double>(out.inliers.size()));
  out.a_from_b = pose;
  const double n_inliers = static_cast<double>(out.inliers.size());
  const double cap = options.max_effective_inliers > 0
                         ? std::min(1.0, options.max_effective_inliers / n_inliers)
                         : 1.0;
  out.information = WithCovarianceFloor(ToResidualOrder(n.h * (cap / out.variance_factor)),
                                        options.floor_translation_mm, options.floor_rotation_deg);
  out.converged = converged && static_cast<int>(out.inliers.size()) >= options.min_inliers;
  return out;
}

}  // namespace sewer3d
