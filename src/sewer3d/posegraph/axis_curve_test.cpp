// The pipe's centreline in the pose graph (axis_curve.hpp): its residuals on exact geometry,
// the station a node's axis point projects to, and a solve that holds a chain of nodes whose
// edges all turn alike onto a straight curve.
#include "sewer3d/posegraph/axis_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sewer3d/posegraph/pose_graph.hpp"
#include "sewer3d/posegraph/solver.hpp"

namespace sewer3d {
namespace {

// Control points every `spacing` mm of arc on a circle of `radius` in the x-z plane.
AxisCurve Arc(double radius, double spacing, int count, double sigma) {
  AxisCurve c;
  c.spacing_mm = spacing;
  for (int k = 0; k < count; ++k) {
    const double a = k * spacing / radius;
    c.points.emplace_back(radius * (1 - std::cos(a)), 0.0, radius * std::sin(a));
  }
  c.curvature_sigma_mm.assign(count - 2, sigma);
  return c;
}

TEST(AxisCurve, ASecondDifferenceIsTheBendAcrossTheChord) {
  const AxisCurve c = Arc(30000.0, 100.0, 5, 0.1);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector4d r = CurvatureResidual(c, k);
    // |D| = 4 R sin²(h / 2R) ≈ h² / R = 0.333 mm across, nothing along.
    EXPECT_NEAR(r.head<3>().norm() * 0.1, 100.0 * 100.0 / 30000.0, 1e-4) << k;
    EXPECT_NEAR(r[3], 0.0, 1e-9) << k;
  }
  const AxisCurve line = Arc(1e12, 100.0, 5, 0.1);
  EXPECT_NEAR(CurvatureResidual(line, 1).norm(), 0.0, 1e-6);
}

TEST(AxisCurve, AnAxisPointSplitsIntoAcrossAndAlong) {
  AxisCurve c = Arc(1e12, 100.0, 4, 0.1);  // the z axis, stations 0 … 300
  AxisObservation o;
  o.in_node = Eigen::Vector3d(0.3, -0.4, 0.0);
  o.station_mm = 140.0;
  o.sigma_mm = 0.1;
  o.along_sigma_mm = 2.0;
  // The node at z = 150 sees the axis 0.5 mm aside (0.3, −0.4) of its own origin at (−0.3,
  // 0.4): the point lies on the axis, 10 mm further along than its station says.
  const Rigid3d node(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.3, 0.4, 150.0));
  const Eigen::Vector4d r = AxisResidual(o, node, c);
  EXPECT_NEAR(r.head<3>().norm(), 0.0, 1e-9);
  EXPECT_NEAR(r[3], 10.0 / 2.0, 1e-9);
  EXPECT_NEAR(ProjectStation(o, node, c), 150.0, 1e-9);
  // Moved 0.2 mm across: 2 σ.
  const Rigid3d aside(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.1, 0.4, 150.0));
  EXPECT_NEAR(AxisResidual(o, aside, c).head<3>().norm(), 2.0, 1e-9);
  EXPECT_NEAR(c.At(-50.0).z(), -50.0, 1e-9);  // extrapolated beyond the ends
}

TEST(AxisCurve, TheGraphRefusesAxisObservationsWithoutACurve) {
  PoseGraph graph;
  graph.SetNode(0, Rigid3d());
  EXPECT_THROW(graph.AddAxisObservation(AxisObservation{}), std::invalid_argument);
  AxisCurve bad = Arc(1e6, 100.0, 4, 0.1);
  bad.curvature_sigma_mm.pop_back();
  EXPECT_THROW(graph.SetAxisCurve(bad), std::invalid_argument);
  bad = Arc(1e6, 100.0, 2, 0.1);
  EXPECT_THROW(graph.SetAxisCurve(bad), std::invalid_argument);
}

// 31 nodes 100 mm apart along z whose edges each turn by 0.01° of yaw (σ 0.01°, translation
// 0.01 mm): alone they bend the chain by up to 3000² · 1.75e-4 / (8 · 100) ≈ 2 mm from its
// chord. Each node also sees the axis at its origin (σ 0.05 mm), and a stiff curve (σ₂ 0.001
// mm) holds the axis straight: the chain's points stay within a tenth of that.
TEST(AxisCurve, AStraightCurveTakesOutATurnEveryEdgeShares) {
  constexpr int kNodes = 31;
  constexpr double kStep = 100.0, kTurn = 0.01 * M_PI / 180.0;
  Matrix6d information = Matrix6d::Identity() * 1e4;                   // 0.01 mm
  information.bottomRightCorner<3, 3>() *= std::pow(0.01 / kTurn, 2);  // 0.01°
  const auto solve = [&](bool with_curve) {
    PoseGraph graph;
    for (int i = 0; i < kNodes; ++i)
      graph.SetNode(i, Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, kStep * i)));
    for (int i = 0; i + 1 < kNodes; ++i) {
      PoseEdge e;
      e.from = i;
      e.to = i + 1;
      e.a_from_b = Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(kTurn, Eigen::Vector3d::UnitY())),
                           Eigen::Vector3d(0, 0, kStep));
      e.information = information;
      graph.AddEdge(e);
    }
    if (with_curve) {
      AxisCurve c = Arc(1e12, kStep, kNodes, 0.001);
      graph.SetAxisCurve(c);
      for (int i = 0; i < kNodes; ++i) {
        AxisObservation o;
        o.node = i;
        o.station_mm = kStep * i;
        graph.AddAxisObservation(o);
      }
    }
    PoseGraphOptions options;
    options.init = PoseGraphInit::kGiven;
    EXPECT_TRUE(OptimisePoseGraph(graph, options).usable);
    double farthest = 0.0;  // from the chord of the first and the last node
    const Eigen::Vector3d a = graph.node(0).translation, b = graph.node(kNodes - 1).translation;
    for (int i = 0; i < kNodes; ++i) {
      const Eigen::Vector3d d = graph.node(i).translation - a;
      farthest =
          std::max(farthest, (d - d.dot((b - a).normalized()) * (b - a).normalized()).norm());
    }
    return farthest;
  };
  const double bent = solve(false), held = solve(true);
  EXPECT_NEAR(bent, 3000.0 * 3000.0 * kTurn / (8.0 * kStep), 0.2);
  EXPECT_LT(held, 0.1 * bent);
}

}  // namespace
}  // namespace sewer3d
