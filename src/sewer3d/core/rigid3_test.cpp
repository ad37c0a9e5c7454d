#include "sewer3d/core/rigid3.hpp"

#include <gtest/gtest.h>

#include <random>

namespace sewer3d {
namespace {

Rigid3d RandomPose(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return {q, Eigen::Vector3d(n(rng), n(rng), n(rng)) * 100.0};
}

TEST(Rigid3, InverseAndCompositionLaws) {
  std::mt19937 rng(7);
  for (int i = 0; i < 100; ++i) {
    const Rigid3d a = RandomPose(rng);
    const Rigid3d b = RandomPose(rng);
    const Eigen::Vector3d p(1.5, -2.0, 40.0);
    EXPECT_LT(((a * a.Inverse()) * p - p).norm(), 1e-9);
    EXPECT_LT(((a * b) * p - a * (b * p)).norm(), 1e-9);
    EXPECT_NEAR(a.rotation.norm(), 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace sewer3d
