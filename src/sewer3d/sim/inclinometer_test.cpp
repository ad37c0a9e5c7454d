// The simulated inclinometer (sim/inclinometer.hpp): its reading is gravity less the carrier's
// acceleration, turned by a constant mounting error, with white noise of the given size.
#include "sewer3d/sim/inclinometer.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sewer3d/core/units.hpp"

namespace sewer3d {
namespace {

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return RadToDeg(std::atan2(a.cross(b).norm(), a.dot(b)));
}

TEST(Inclinometer, ReadsGravityLessTheCarriersAccelerationWithMountingAndNoise) {
  PipeWorld world;
  world.sections = {{.length_mm = 3000.0, .diameter_mm = 300.0}};
  const PipeGeometry pipe(world);
  MotionOptions motion;
  motion.travel_mm = 1500.0;
  const Trajectory trajectory(pipe, motion, 5);
  InclinometerOptions exact;
  exact.noise_deg = exact.mounting_deg = 0.0;
  const auto clean = SimulateInclinometer(trajectory, exact, 9);
  ASSERT_EQ(clean.size(), static_cast<size_t>(std::floor(trajectory.DurationS() * 20.0)) + 1);
  double largest = 0.0;
  for (const InclinometerSample& s : clean) {
    // The true down is the world's +y seen from the carrier, which rolls about 2° ± 1.5°.
    EXPECT_NEAR(s.true_down.norm(), 1.0, 1e-12);
    const Eigen::Vector3d up_in_world =
        trajectory.WorldFromCarrier(s.time_s).rotation * s.true_down;
    EXPECT_LT((up_in_world - Eigen::Vector3d::UnitY()).norm(), 1e-12);
    // Only the acceleration across gravity tilts the reading: by atan(a⊥ / g).
    const Eigen::Vector3d a = s.acceleration_mm_s2;
    const double across = std::hypot(a.x(), a.z());
    EXPECT_NEAR(AngleDeg(s.measured_down, s.true_down),
                RadToDeg(std::atan2(across, kGravityMmS2 - a.y())), 1e-6);
    largest = std::max(largest, AngleDeg(s.measured_down, s.true_down));
  }
  // Speed ±5 % every 2.3 s and a 2 mm wander: a few hundredths of a degree.
  EXPECT_GT(largest, 0.02);
  EXPECT_LT(largest, 0.3);

  // Mounting: the same turn of every reading; noise: 0.01° per axis, 0.014° in all (RMS).
  InclinometerOptions mounted = exact;
  mounted.mounting_deg = 0.1;
  const auto turned = SimulateInclinometer(trajectory, mounted, 9);
  InclinometerOptions noisy = exact;
  noisy.noise_deg = 0.01;
  const auto read = SimulateInclinometer(trajectory, noisy, 9);
  const double first = AngleDeg(turned[0].measured_down, clean[0].measured_down);
  EXPECT_GT(first, 0.005);
  double sum = 0.0;
  for (size_t i = 0; i < clean.size(); ++i) {
    EXPECT_NEAR(AngleDeg(turned[i].measured_down, clean[i].measured_down), first, 0.002);
    sum += std::pow(AngleDeg(read[i].measured_down, clean[i].measured_down), 2);
  }
  EXPECT_NEAR(std::sqrt(sum / clean.size()), 0.01 * std::sqrt(2.0), 0.003);

  InclinometerOptions off;
  off.enabled = false;
  EXPECT_TRUE(SimulateInclinometer(trajectory, off, 9).empty());
  noisy.noise_deg = 2.0;
  EXPECT_THROW(SimulateInclinometer(trajectory, noisy, 9), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
