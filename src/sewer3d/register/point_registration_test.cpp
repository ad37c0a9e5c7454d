#include "sewer3d/register/point_registration.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <random>

#include "sewer3d/register/information.hpp"
#include "sewer3d/register/rigid_fit.hpp"
#include "sewer3d/testing/matchers.hpp"

namespace sewer3d {
namespace {

using testing::PoseNear;

Rigid3d SomePose() {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, -1.0, 0.5).normalized()));
  return {q, Eigen::Vector3d(12.0, -40.0, 3.5)};
}

// Points of a pipe wall patch in front of camera a (z ≈ 150 mm, ±60 × ±45 mm).
std::vector<Eigen::Vector3d> WallPoints(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> x(-60.0, 60.0), y(-45.0, 45.0);
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < n; ++i) {
    const double px = x(rng), py = y(rng);
    out.emplace_back(px, py, 150.0 - 0.003 * px * px);
  }
  return out;
}

TEST(RigidFit, ThreePointSolverIsExactOnNoiseFreePoints) {
  const Rigid3d truth = SomePose();
  const Eigen::Vector3d src[3] = {{1, 2, 150}, {40, -10, 140}, {-30, 25, 155}};
  const Eigen::Vector3d dst[3] = {truth * src[0], truth * src[1], truth * src[2]};
  const auto fit = RigidFromThreePoints(src, dst);
  ASSERT_TRUE(fit.has_value());
  EXPECT_THAT(*fit, PoseNear(truth, 1e-9, 1e-9));
  const Eigen::Vector3d line[3] = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  EXPECT_FALSE(RigidFromThreePoints(line, dst).has_value());
}

TEST(RigidFit, UmeyamaIsExactOnNoiseFreePointsAndRefusesCollinear) {
  std::mt19937_64 rng(1);
  const Rigid3d truth = SomePose();
  const std::vector<Eigen::Vector3d> src = WallPoints(50, rng);
  std::vector<Eigen::Vector3d> dst;
  for (const auto& p : src) dst.push_back(truth * p);
  const auto fit = UmeyamaFit(src, dst);
  ASSERT_TRUE(fit.has_value());
  EXPECT_THAT(*fit, PoseNear(truth, 1e-9, 1e-9));
  std::vector<double> weights(src.size(), 0.5);
  weights[3] = 7.0;
  EXPECT_THAT(*UmeyamaFit(src, dst, weights), PoseNear(truth, 1e-9, 1e-9));
  const std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
  EXPECT_FALSE(UmeyamaFit(line, line).has_value());
}

// The convention of information.hpp: a measurement off the truth by δ = (δt, δθ) gives the
// pose graph residual [−δt; δθ] at the true poses.
TEST(Information, UpdateConventionMatchesThePoseGraphResidual) {
  const Rigid3d truth = SomePose();
  Vector6d delta;
  delta << 1e-4, -2e-4, 3e-4, 2e-6, -1e-6, 3e-6;
  PoseEdge edge;
  edge.a_from_b = ApplyUpdate(truth, delta);
  const Vector6d r = EdgeResidual(edge, Rigid3d::Identity(), truth);
  Vector6d expected;
  expected << -delta.head<3>(), delta.tail<3>();
  EXPECT_LT((r - expected).norm(), 1e-10);
}

Eigen::Vector3d Sample(const Eigen::Matrix3d& cov, std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return cov.llt().matrixL() * Eigen::Vector3d(n(rng), n(rng), n(rng));
}

// Noisy matches drawn from the noise model, 20 % gross outliers: the pose is recovered, the
// outliers are rejected, and the normalised estimation error squared (6 DoF) has mean ≈ 6.
TEST(PointRegistration, RecoversPoseAndItsInformationIsHonest) {
  const DepthNoiseModel noise;
  const double focal_px = 415.0;
  const Rigid3d truth = SomePose();  // a_from_b
  PointRegistrationOptions options;
  // Only the noise model here: no systematic error to cover, so no covariance floor.
  options.floor_translation_mm = 0.0;
  options.floor_rotation_deg = 0.0;
  double nees_sum = 0.0;
  const int trials = 200;
  for (int trial = 0; trial < trials; ++trial) {
    std::mt19937_64 rng(100 + trial);
    std::vector<PointMatch> matches;
    for (const Eigen::Vector3d& p_a : WallPoints(150, rng)) {
      PointMatch m;
      const Eigen::Vector3d p_b = truth.Inverse() * p_a;
      m.cov_a = noise.PointCovariance(p_a, focal_px);
      m.cov_b = noise.PointCovariance(p_b, focal_px);
      m.a = p_a + Sample(m.cov_a, rng);
      m.b = p_b + Sample(m.cov_b, rng);
      if (matches.size() % 5 == 0) m.b += Eigen::Vector3d(5.0, -3.0, 2.0);  // outlier
      matches.push_back(m);
    }
    options.seed = trial + 1;
    const PointRegistrationResult r = RegisterPoints(matches, options);
    ASSERT_TRUE(r.converged);
    // 1 σ ≈ 0.015 mm and 0.02° here (0.15 mm per match over 120 inliers, ±60 mm levers).
    EXPECT_THAT(r.a_from_b, PoseNear(truth, 0.1, 0.1));
    EXPECT_NEAR(static_cast<int>(r.inliers.size()), 120, 3);
    PoseEdge edge;
    edge.a_from_b = r.a_from_b;
    const Vector6d e = EdgeResidual(edge, Rigid3d::Identity(), truth);
    nees_sum += e.dot(r.information * e);
  }
  // Mean of 200 χ²(6) values: 6 ± 0.25 (1 σ).
  EXPECT_NEAR(nees_sum / trials, 6.0, 1.0);
  RecordProperty("mean_nees", std::to_string(nees_sum / trials));
}

TEST(PointRegistration, TooFewMatchesIsNotConverged) {
  std::vector<PointMatch> matches(5);
  EXPECT_FALSE(RegisterPoints(matches, PointRegistrationOptions{}).converged);
  PointRegistrationOptions bad;
  bad.ransac_confidence = 1.0;
  EXPECT_THROW(RegisterPoints(matches, bad), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
