// The edge of a pair record: pairs of two modules get the between-modules covariance floor
// (each module's own calibration error), pairs of one module keep their information.
#include "sewer3d/pipeline/register_pairs.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sewer3d/core/units.hpp"

namespace sewer3d {
namespace {

// A record whose information is that of σ 0.02 mm per axis and 0.005° per rotation, with the
// translation along y (a cylinder's slide) unconstrained.
PairRecord Record(int a_module, int b_module) {
  PairRecord r;
  r.a_module = a_module;
  r.b_module = b_module;
  r.method = "projection";
  Vector6d d;
  const double rot = 0.005 * kRadPerDeg;
  d << 1 / (0.02 * 0.02), 0.0, 1 / (0.02 * 0.02), 1 / (rot * rot), 1 / (rot * rot), 1 / (rot * rot);
  r.information = d.asDiagonal();
  return r;
}

TEST(PairEdge, TwoModulesGetTheBetweenModulesFloor) {
  const PairRegistrationOptions options;
  const std::optional<RegistrationEdge> e = PairEdge(Record(0, 1), NeighbourPair{}, options);
  ASSERT_TRUE(e.has_value());
  const double sigma_t = std::hypot(0.02, options.between_modules_floor_mm);
  const double sigma_r = std::hypot(0.005, options.between_modules_floor_deg) * kRadPerDeg;
  EXPECT_NEAR(e->information(0, 0), 1 / (sigma_t * sigma_t), 1e-6 / (sigma_t * sigma_t));
  EXPECT_NEAR(e->information(3, 3), 1 / (sigma_r * sigma_r), 1e-6 / (sigma_r * sigma_r));
  // The unconstrained slide gains nothing from the floor (only the solver's vanishing one).
  EXPECT_LT(e->information(1, 1), 1e-5);
}

TEST(PairEdge, OneModuleKeepsItsInformation) {
  const PairRecord r = Record(2, 2);
  const std::optional<RegistrationEdge> e = PairEdge(r, NeighbourPair{}, PairRegistrationOptions{});
  ASSERT_TRUE(e.has_value());
  EXPECT_NEAR(e->information(0, 0), r.information(0, 0), 1e-9 * r.information(0, 0));
  EXPECT_NEAR(e->information(5, 5), r.information(5, 5), 1e-9 * r.information(5, 5));
}

TEST(PairEdge, AFailedPairHasNoEdge) {
  PairRecord r = Record(0, 1);
  r.method = "none";
  EXPECT_FALSE(PairEdge(r, NeighbourPair{}, PairRegistrationOptions{}).has_value());
}

}  // namespace
}  // namespace sewer3d
