#include "sewer3d/model/centreline_fit.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

#include "sewer3d/model/unroll.hpp"

namespace sewer3d {
namespace {

constexpr double kPi = std::numbers::pi;

// A pipe whose true axis is an arc of radius `bend_mm` (∞: straight) through (4, −3, 0) with a
// tilted start tangent, so that station s of the truth is arc length from z = 0.
struct TruePipe {
  double bend_mm = 30000.0;
  double radius_mm = 151.2;  // the true mean radius; the nominal is 150
  Eigen::Vector3d p0{4.0, -3.0, 0.0};
  Eigen::Vector3d t0 = Eigen::Vector3d(0.012, 0.017, 1.0).normalized();
  Eigen::Vector3d n0 = (Eigen::Vector3d::UnitX() - t0.x() * t0).normalized();

  [[nodiscard]] Eigen::Vector3d Axis(double s) const {
    if (std::isinf(bend_mm)) return p0 + s * t0;
    return p0 + bend_mm * std::sin(s / bend_mm) * t0 + bend_mm * (1 - std::cos(s / bend_mm)) * n0;
  }
  [[nodiscard]] Eigen::Vector3d Tangent(double s) const {
    if (std::isinf(bend_mm)) return t0;
    return std::cos(s / bend_mm) * t0 + std::sin(s / bend_mm) * n0;
  }
  [[nodiscard]] Eigen::Vector3d Normal(double s) const { return t0.cross(n0).cross(Tangent(s)); }
  [[nodiscard]] Eigen::Vector3d Wall(double s, double theta, double radial_mm) const {
    const Eigen::Vector3d b = t0.cross(n0);
    return Axis(s) + radial_mm * (std::cos(theta) * Normal(s) + std::sin(theta) * b);
  }
  // Truth station and lateral distance of an axis point estimate.
  [[nodiscard]] std::pair<double, double> Nearest(const Eigen::Vector3d& p, double s) const {
    for (int i = 0; i < 20; ++i) s += (p - Axis(s)).dot(Tangent(s));
    return {s, (p - Axis(s)).norm()};
  }
};

// Radial offset (mm, positive outward) of everything that is not round pipe.
double Defects(double s, double theta) {
  double d = 0.0;
  const double wall = 151.2;
  d += 0.03 * wall * std::cos(2 * theta);  // 6 % ovality
  d -= 3.0 * std::exp(-(std::pow(s - 800, 2) + std::pow(wall * (theta - 1.0), 2)) / 450.0);  // bump
  if (s > 1500 && s < 1515) d += 5.0;                                         // joint gap
  if (s > 1515 && s < 1600 && std::abs(theta - kPi / 2) < kPi / 4) d -= 2.5;  // joint step
  if (s > 2000 && s < 2400 && std::abs(theta - kPi) < 0.6) d -= 12.0;         // deposit
  if (std::hypot(s - 1000, wall * (theta - 0.8)) < 40.0) d -= 35.0;           // intrusion
  if (s > 400 && s < 500 && theta > 2.0 && theta < 2.6) d += 4.0;             // spalling
  return d;
}

std::vector<Eigen::Vector3d> SamplePipe(const TruePipe& pipe, bool defects, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> station(-100.0, 2900.0), theta(0.0, 2 * kPi);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 60000; ++i) {
    const double s = station(rng), t = theta(rng);
    const double r = pipe.radius_mm + (defects ? Defects(s, t) : 0.0) + noise(rng);
    points.push_back(pipe.Wall(s, t, r));
  }
  return points;
}

struct AxisError {
  double lateral_mm = 0.0, station_mm = 0.0;
};

AxisError CompareAxis(const TruePipe& pipe, const Centreline& line, double from, double to) {
  AxisError worst;
  for (double s = from; s <= to; s += 10.0) {
    const auto [truth_s, lateral] = pipe.Nearest(line.FrameAt(s).origin, s);
    worst.lateral_mm = std::max(worst.lateral_mm, lateral);
    worst.station_mm = std::max(worst.station_mm, std::abs(truth_s - s));
  }
  return worst;
}

TEST(FitCentreline, FollowsABendThroughDefectsAndOvality) {
  const TruePipe pipe;
  CentrelineFitOptions options;
  const CentrelineFit fit = FitCentreline(SamplePipe(pipe, true, 11), options);
  ASSERT_TRUE(fit.converged);
  const AxisError error = CompareAxis(pipe, fit.centreline, -50.0, 2850.0);
  EXPECT_LT(error.lateral_mm, 0.1);
  EXPECT_LT(error.station_mm, 0.2);
  EXPECT_NEAR(fit.report.radius_mm, pipe.radius_mm, 0.05);
  EXPECT_DOUBLE_EQ(fit.centreline.radius_mm, 150.0);  // the model radius is the nominal one
  ASSERT_TRUE(fit.report.bend_radius_mm.has_value());
  EXPECT_NEAR(*fit.report.bend_radius_mm, pipe.bend_mm, 0.05 * pipe.bend_mm);
  EXPECT_NEAR(fit.report.rms_mm, 0.1, 0.02);
  EXPECT_GE(fit.report.slices_used, 95);
  // Ovality is not fitted away: the slices see the 2θ amplitude of 3 % of the radius.
  EXPECT_NEAR(fit.report.slices[50].ovality_mm, 0.03 * pipe.radius_mm, 0.1);
  // Clock 12 is the model frame's −y perpendicular to the tangent.
  const AxisFrame f = fit.centreline.FrameAt(0.0);
  const Eigen::Vector3d up = -Eigen::Vector3d::UnitY();
  EXPECT_LT((f.crown - (up - up.dot(f.tangent) * f.tangent).normalized()).norm(), 1e-9);
  std::printf(
      "bent: lateral %.4f mm, station %.5f mm, radius %.4f mm, bend %.0f mm, rms %.4f, "
      "slices %d/%d, iterations %d\n",
      error.lateral_mm, error.station_mm, fit.report.radius_mm, *fit.report.bend_radius_mm,
      fit.report.rms_mm, fit.report.slices_used, fit.report.slices_rejected, fit.report.iterations);
}

TEST(FitCentreline, StraightCylinderAndStartStation) {
  TruePipe pipe;
  pipe.bend_mm = std::numeric_limits<double>::infinity();
  CentrelineFitOptions options;
  options.straight = true;
  options.start_station_mm = 1000.0;
  const CentrelineFit fit = FitCentreline(SamplePipe(pipe, true, 12), options);
  ASSERT_TRUE(fit.converged);
  EXPECT_FALSE(fit.report.bend_radius_mm.has_value());
  Centreline shifted = fit.centreline;
  shifted.station0_mm -= 1000.0;  // compare in the truth's stations
  const AxisError error = CompareAxis(pipe, shifted, -100.0, 2900.0);
  EXPECT_LT(error.lateral_mm, 0.05);
  EXPECT_LT(error.station_mm, 0.05);
  EXPECT_NEAR(fit.report.radius_mm, pipe.radius_mm, 0.05);
  EXPECT_NEAR(Unroll(fit.centreline, pipe.Axis(0.0) + 100.0 * pipe.Normal(0.0), 0.0).station_mm,
              1000.0, 0.05);
  std::printf("straight: lateral %.4f mm, station %.5f mm, radius %.4f mm\n", error.lateral_mm,
              error.station_mm, fit.report.radius_mm);
}

TEST(FitCentreline, TooFewPointsIsNotConverged) {
  std::vector<Eigen::Vector3d> points(20, Eigen::Vector3d(150, 0, 0));
  EXPECT_FALSE(FitCentreline(points, CentrelineFitOptions{}).converged);
  CentrelineFitOptions bad;
  bad.slice_spacing_mm = 0.0;
  EXPECT_THROW(FitCentreline(points, bad), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
