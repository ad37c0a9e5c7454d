#include "sewer3d/posegraph/pose_graph.hpp"

#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "sewer3d/core/units.hpp"
#include "sewer3d/posegraph/edge_cost.hpp"
#include "sewer3d/posegraph/solver.hpp"
#include "sewer3d/testing/test_graphs.hpp"

namespace sewer3d {
namespace {

using namespace test_graphs;  // NOLINT: the synthetic graphs of this module's tests

TEST(EdgeCost, JacobiansMatchFiniteDifferences) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const Rigid3d a = RandomPose(rng, 100.0), b = RandomPose(rng, 100.0);
    const Rigid3d measured = Perturb(a.Inverse() * b, rng, 0.05, 2.0);
    std::unique_ptr<ceres::CostFunction> cost(
        EdgeCost::Create(measured, SqrtInformation(RandomInformation(rng))));
    ceres::EigenQuaternionManifold quaternion;
    const std::vector<const ceres::Manifold*> manifolds = {nullptr, &quaternion, nullptr,
                                                           &quaternion};
    ceres::GradientChecker checker(cost.get(), &manifolds, ceres::NumericDiffOptions());
    const double* parameters[] = {a.translation.data(), a.rotation.coeffs().data(),
                                  b.translation.data(), b.rotation.coeffs().data()};
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(parameters, 1e-7, &results)) << results.error_log;
  }
}

TEST(EdgeCost, AgreesWithEdgeResidualAndVanishesAtTheMeasurement) {
  std::mt19937 rng(2);
  const Rigid3d a = RandomPose(rng, 50.0), b = RandomPose(rng, 50.0);
  PoseEdge edge;
  edge.a_from_b = a.Inverse() * b;
  EXPECT_LT(EdgeResidual(edge, a, b).norm(), 1e-12);
  edge.a_from_b = Perturb(edge.a_from_b, rng, 0.01, 1.0);
  const Matrix6d sqrt_info = SqrtInformation(edge.information);
  std::unique_ptr<ceres::CostFunction> cost(EdgeCost::Create(edge.a_from_b, sqrt_info));
  const double* parameters[] = {a.translation.data(), a.rotation.coeffs().data(),
                                b.translation.data(), b.rotation.coeffs().data()};
  Eigen::Matrix<double, 6, 1> r;
  ASSERT_TRUE(cost->Evaluate(parameters, r.data(), nullptr));
  EXPECT_LT((r - sqrt_info * EdgeResidual(edge, a, b)).norm(), 1e-12);
}

TEST(EdgeCost, TheSignOfAQuaternionDoesNotChangeTheCostOrTheOptimum) {
  // q and -q are one rotation; g2o files and solver steps may write either. With full 6x6
  // information (translation-rotation cross terms) a sign-dependent residual would move
  // the optimum.
  std::mt19937 rng(9);
  std::vector<Rigid3d> truth;
  for (int i = 0; i < 12; ++i) truth.push_back(RandomPose(rng, 100.0));
  PoseGraph graph = RingGraph(truth, rng, 0.01, 0.5);
  for (PoseEdge& e : graph.mutable_edges()) e.information = RandomInformation(rng);
  PoseGraph negated = graph;
  for (PoseEdge& e : negated.mutable_edges()) e.a_from_b.rotation.coeffs() *= -1.0;
  for (int i = 0; i < 12; i += 2) negated.mutable_node(i).rotation.coeffs() *= -1.0;
  EXPECT_NEAR(GraphCost(negated), GraphCost(graph), 1e-9 * GraphCost(graph));
  PoseGraphOptions options;
  options.init = PoseGraphInit::kGiven;
  ASSERT_TRUE(OptimisePoseGraph(graph, options).usable);
  ASSERT_TRUE(OptimisePoseGraph(negated, options).usable);
  for (int i = 0; i < 12; ++i) {
    EXPECT_LT((negated.node(i).translation - graph.node(i).translation).norm(), 1e-4) << i;
    EXPECT_LT(RotationErrorDeg(negated.node(i), graph.node(i)), 1e-5) << i;
  }
}

TEST(Optimise, ConvergesFromLargePerturbationsToTheOptimumNearTheTruth) {
  std::mt19937 rng(3);
  std::vector<Rigid3d> truth;
  for (int i = 0; i < 40; ++i) {
    const double angle = kTwoPi * i / 40;
    truth.push_back({Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())),
                     Eigen::Vector3d(500.0 * std::cos(angle), 500.0 * std::sin(angle), 0.0)});
  }
  // Edge noise 0.002 rad per axis and 0.5 mm: the optimum itself lies off the truth.
  const PoseGraph measured = RingGraph(truth, rng, 0.002, 0.5);
  PoseGraph from_truth = measured, perturbed = measured;
  for (int i = 1; i < 40; ++i) perturbed.mutable_node(i) = Perturb(truth[i], rng, 0.2, 30.0);
  PoseGraphOptions options;
  options.init = PoseGraphInit::kGiven;
  const PoseGraphReport reference = OptimisePoseGraph(from_truth, options);
  const PoseGraphReport report = OptimisePoseGraph(perturbed, options);
  ASSERT_TRUE(report.usable && reference.usable) << report.termination;
  EXPECT_LT(report.final_cost, 1e-3 * report.initial_cost);
  EXPECT_NEAR(report.final_cost, reference.final_cost, 1e-6 * reference.final_cost);
  for (int i = 0; i < 40; ++i) {
    // Same optimum from 11° / 30 mm perturbations as from the truth.
    EXPECT_LT((perturbed.node(i).translation - from_truth.node(i).translation).norm(), 0.01);
    EXPECT_LT(RotationErrorDeg(perturbed.node(i), from_truth.node(i)), 1e-3);
    // The optimum's distance to the truth: a random walk over <= 20 edges of 0.2° each,
    // shortened by the loop closures; 3 sigma is about 2.7° and 24 mm at 500 mm.
    EXPECT_LT(RotationErrorDeg(from_truth.node(i), truth[i]), 2.7) << i;
    EXPECT_LT((from_truth.node(i).translation - truth[i].translation).norm(), 24.0) << i;
  }
  // Node 0 holds the gauge.
  EXPECT_LT((perturbed.node(0).translation - truth[0].translation).norm(), 1e-12);
}

TEST(Chordal, ExactOnNoiseFreeGraphsFromArbitraryStart) {
  std::mt19937 rng(4);
  std::vector<Rigid3d> truth;
  for (int i = 0; i < 30; ++i) truth.push_back(RandomPose(rng, 200.0));
  PoseGraph graph = RingGraph(truth, rng, 0.0, 0.0);
  for (int i = 1; i < 30; ++i) graph.mutable_node(i) = RandomPose(rng, 200.0);
  ASSERT_TRUE(ChordalInitialisation(graph));
  for (int i = 0; i < 30; ++i) {
    EXPECT_LT((graph.node(i).translation - truth[i].translation).norm(), 1e-6);
    EXPECT_LT(RotationErrorDeg(graph.node(i), truth[i]), 1e-6);
  }
  EXPECT_LT(GraphCost(graph), 1e-12);
}

TEST(Chordal, RefusesDisconnectedGraph) {
  std::mt19937 rng(5);
  std::vector<Rigid3d> truth;
  for (int i = 0; i < 10; ++i) truth.push_back(RandomPose(rng, 100.0));
  PoseGraph graph = RingGraph(truth, rng, 0.0, 0.0);
  graph.SetNode(99, RandomPose(rng, 10.0));  // no edge reaches it
  const Rigid3d before = graph.node(3);
  EXPECT_FALSE(ChordalInitialisation(graph));
  EXPECT_LT((graph.node(3).translation - before.translation).norm(), 1e-12);
}

TEST(Optimise, CountsTheNodesNoEdgeLinksToAnAnchor) {
  std::mt19937 rng(5);
  std::vector<Rigid3d> truth;
  for (int i = 0; i < 10; ++i) truth.push_back(RandomPose(rng, 100.0));
  PoseGraph graph = RingGraph(truth, rng, 0.001, 0.2);
  PoseGraphOptions options;
  options.init = PoseGraphInit::kGiven;
  EXPECT_TRUE(OptimisePoseGraph(graph, options).usable);
  graph.SetNode(99, RandomPose(rng, 10.0));  // no edge reaches it
  const Rigid3d alone = graph.node(99);
  const PoseGraphReport report = OptimisePoseGraph(graph, options);
  EXPECT_EQ(report.unanchored_nodes, 1);
  EXPECT_LT((graph.node(99).translation - alone.translation).norm(), 1e-12);  // kept as given
  graph.fixed_nodes() = {0, 99};  // fixed, its pose is given
  EXPECT_EQ(OptimisePoseGraph(graph, options).unanchored_nodes, 0);
  PoseGraph single;
  single.SetNode(0, truth[0]);
  const PoseGraphReport one = OptimisePoseGraph(single, options);
  EXPECT_TRUE(one.usable);
  EXPECT_EQ(one.iterations, 0);
}

TEST(Optimise, HuberLossResistsAWrongRegistration) {
  std::mt19937 rng(6);
  std::vector<Rigid3d> truth;
  for (int i = 0; i < 20; ++i) {
    truth.push_back({Eigen::Quaterniond::Identity(), Eigen::Vector3d(100.0 * i, 0.0, 0.0)});
  }
  // Returns the graph's poses after optimisation, with or without an 80 mm wrong edge.
  auto solve = [&](double huber, bool with_wrong_edge) {
    std::mt19937 local(7);
    PoseGraph graph = RingGraph(truth, local, 0.001, 0.2);
    if (with_wrong_edge) {
      PoseEdge wrong;
      wrong.from = 2;
      wrong.to = 12;
      wrong.a_from_b = {Eigen::Quaterniond::Identity(), Eigen::Vector3d(1080.0, 0.0, 0.0)};
      wrong.information.diagonal() << 1, 1, 1, 400, 400, 400;
      graph.AddEdge(wrong);
    }
    PoseGraphOptions options;
    options.huber_delta = huber;
    OptimisePoseGraph(graph, options);
    return graph;
  };
  auto max_distance = [](const PoseGraph& a, const PoseGraph& b) {
    double worst = 0.0;
    for (const auto& [id, pose] : a.nodes()) {
      worst = std::max(worst, (pose.translation - b.node(id).translation).norm());
    }
    return worst;
  };
  const PoseGraph clean = solve(0.0, false);
  // The wrong edge drags a plain least-squares solution by many millimetres. A Huber loss
  // (scale 1 sigma) caps the edge's pull at 1 sigma instead of 80, so the displacement it
  // causes shrinks accordingly (the chain responds nearly linearly).
  const double plain = max_distance(solve(0.0, true), clean);
  const double robust = max_distance(solve(1.0, true), clean);
  EXPECT_GT(plain, 20.0);
  EXPECT_LT(robust, plain / 20.0) << "plain " << plain;
}

// Ten poses 10 mm apart along x, each step measured twice (σ 0.01 mm, 0.01 rad); the measurements
// of `groups` (one list per bias group, by step set) read every step 0.2 mm long.
PoseGraph TwiceMeasuredSteps(const std::vector<double>& set_bias_mm,
                             const std::vector<int>& group) {
  PoseGraph graph;
  for (int i = 0; i < 10; ++i)
    graph.SetNode(i, {Eigen::Quaterniond::Identity(), Eigen::Vector3d(10.0 * i, 0.0, 0.0)});
  EdgeBias prior;
  prior.prior_information.diagonal() << 1, 1, 1, 1, 1, 1;  // σ 1 mm, 1 rad: weak
  for (int g : group) {
    if (g >= 0 && graph.biases().count(g) == 0) graph.SetBias(g, prior);
  }
  for (size_t set = 0; set < set_bias_mm.size(); ++set) {
    for (int i = 0; i + 1 < 10; ++i) {
      PoseEdge e;
      e.from = i;
      e.to = i + 1;
      e.a_from_b = {Eigen::Quaterniond::Identity(), Eigen::Vector3d(10.0 + set_bias_mm[set], 0, 0)};
      e.information.diagonal() << 1e4, 1e4, 1e4, 1e4, 1e4, 1e4;
      e.bias = group[set];
      graph.AddEdge(e);
    }
  }
  graph.fixed_nodes() = {0};
  return graph;
}

TEST(Optimise, EstimatesTheBiasAGroupOfEdgesShares) {
  // Exact steps and steps 0.2 mm long: alone, least squares splits the difference.
  PoseGraph plain = TwiceMeasuredSteps({0.0, 0.2}, {-1, -1});
  PoseGraphOptions options;
  options.init = PoseGraphInit::kGiven;
  ASSERT_TRUE(OptimisePoseGraph(plain, options).usable);
  EXPECT_NEAR(plain.node(9).translation.x(), 90.0 + 9 * 0.1, 1e-3);
  // The long ones as a bias group: the bias takes the 0.2 mm (shrunk by the weak prior: 9 edges
  // of 1e4 against 1), and the steps are exact.
  PoseGraph biased = TwiceMeasuredSteps({0.0, 0.2}, {-1, 0});
  const PoseGraphReport report = OptimisePoseGraph(biased, options);
  ASSERT_TRUE(report.usable);
  EXPECT_NEAR(biased.node(9).translation.x(), 90.0, 1e-3);
  EXPECT_NEAR(biased.biases().at(0).value.x(), -0.2, 1e-3);  // r − b = 0 with r = −0.2
  EXPECT_NEAR(biased.biases().at(0).value.tail<5>().norm(), 0.0, 1e-6);
  EXPECT_NEAR(report.final_cost, GraphCost(biased), 1e-9);
  EXPECT_NEAR(report.final_cost, 0.5 * 0.2 * 0.2, 1e-3);  // the prior's term: the edges fit
  // Both sets biased alike, in two groups held to a zero sum: the common part stays in the
  // poses (the data say the steps are 10.2 mm), not in the biases.
  PoseGraph both = TwiceMeasuredSteps({0.2, 0.2}, {0, 1});
  both.AddZeroSum(
      {{0, 1}, {Matrix6d::Identity(), Matrix6d::Identity()}, Matrix6d::Identity() * 1e6});
  ASSERT_TRUE(OptimisePoseGraph(both, options).usable);
  EXPECT_NEAR(both.node(9).translation.x(), 90.0 + 9 * 0.2, 1e-3);
  EXPECT_NEAR(both.biases().at(0).value.norm(), 0.0, 1e-4);
  EXPECT_NEAR(both.biases().at(1).value.norm(), 0.0, 1e-4);
  // A graph with biases is not a pose graph: no certificate.
  options.certify = true;
  const PoseGraphReport certified = OptimisePoseGraph(biased, options);
  EXPECT_FALSE(certified.certificate_applicable);
  EXPECT_NE(certified.certificate_reason.find("bias"), std::string::npos);
}

TEST(PoseGraph, RefusesEdgesOfABiasGroupNotSet) {
  PoseGraph graph;
  graph.SetNode(0, Rigid3d());
  graph.SetNode(1, Rigid3d());
  PoseEdge e;
  e.to = 1;
  e.bias = 3;
  EXPECT_THROW(graph.AddEdge(e), std::invalid_argument);
  EXPECT_THROW(graph.AddZeroSum({{3}, {Matrix6d::Identity()}, Matrix6d::Identity()}),
               std::invalid_argument);
}

// A straight run of 20 poses 100 mm apart, measured with 0.1 mm and 1 mrad of noise and
// information to match, so the χ² of a sound edge is a few units.
PoseGraph NoisyRun(unsigned seed) {
  std::vector<Rigid3d> truth;
  for (int i = 0; i < 20; ++i)
    truth.push_back({Eigen::Quaterniond::Identity(), Eigen::Vector3d(100.0 * i, 0.0, 0.0)});
  std::mt19937 rng(seed);
  return RingGraph(truth, rng, 0.001, 0.1, [](std::mt19937&) {
    Matrix6d information = Matrix6d::Zero();
    information.diagonal() << 100, 100, 100, 2.5e5, 2.5e5, 2.5e5;  // σ 0.1 mm, 2 mrad (2 vec)
    return information;
  });
}

TEST(OutlierEdge, FindsTheOneMeasurementTheOthersContradict) {
  PoseGraph sound = NoisyRun(7);
  OptimisePoseGraph(sound, {});
  EXPECT_FALSE(FindOutlierEdge(sound).has_value());
  // One registration (σ 1 mm) written in metres (1.0 for 1000 mm): the optimum is a compromise
  // that leaves most of its 1 m on that edge.
  PoseGraph metres = NoisyRun(7);
  PoseEdge wrong;
  wrong.information.diagonal() << 1, 1, 1, 2500, 2500, 2500;
  wrong.from = 2;
  wrong.to = 12;
  wrong.a_from_b = {Eigen::Quaterniond::Identity(), Eigen::Vector3d(1.0, 0.0, 0.0)};
  metres.AddEdge(wrong);
  OptimisePoseGraph(metres, {});
  const std::optional<OutlierEdge> outlier = FindOutlierEdge(metres);
  ASSERT_TRUE(outlier.has_value());
  EXPECT_EQ(outlier->index, metres.edges().size() - 1);
  EXPECT_GT(outlier->chi2, 1e5);  // hundreds of mm left on an edge of σ 1 mm
  EXPECT_LT(outlier->median_chi2, 1e3);
}

TEST(GraphCost, EdgesWrittenTheOtherWayRoundFitTheirInverse) {
  PoseGraph graph = NoisyRun(8);
  const double as_written = GraphCost(graph), inverted = GraphCostEdgesInverted(graph);
  EXPECT_LT(as_written, 10.0 * static_cast<double>(graph.edges().size()));
  EXPECT_GT(inverted, 1e4 * as_written);
  // From and to swapped, measurement kept: the same numbers change roles.
  PoseGraph swapped = graph;
  for (PoseEdge& e : swapped.mutable_edges()) std::swap(e.from, e.to);
  // (the noise, measured in the other node's frame, weighs a little differently).
  EXPECT_LT(GraphCostEdgesInverted(swapped), 3.0 * inverted / 1e4 + 10.0 * as_written);
  EXPECT_GT(GraphCost(swapped), 100.0 * GraphCostEdgesInverted(swapped));
}

TEST(PoseGraph, RegularisationEdgeKeepsAStraightPipeStraight) {
  // Odometry-like chain whose edges all carry the same small yaw bias: the chain curls.
  // A regularisation edge first -> last ("the pipe is straight") pulls it back.
  std::mt19937 rng(8);
  PoseGraph graph;
  const int n = 11;
  const Rigid3d step(Eigen::Quaterniond(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitZ())),
                     Eigen::Vector3d(100.0, 0.0, 0.0));
  Rigid3d pose;
  for (int i = 0; i < n; ++i) {
    graph.SetNode(i, pose);
    pose = pose * step;
  }
  for (int i = 0; i + 1 < n; ++i) {
    PoseEdge e;
    e.from = i;
    e.to = i + 1;
    e.a_from_b = step;
    graph.AddEdge(e);
  }
  Matrix6d covariance = Matrix6d::Identity();
  covariance.diagonal() << 1.0, 1.0, 1.0, 1e-6, 1e-6, 1e-6;  // 1 mm, 0.06°
  graph.AddRegularisationEdge(
      0, n - 1, {Eigen::Quaterniond::Identity(), Eigen::Vector3d(1000.0, 0, 0)}, covariance);
  EXPECT_EQ(graph.edges().back().kind, EdgeKind::kRegularisation);
  const double lateral_before = std::abs(graph.node(n - 1).translation.y());
  OptimisePoseGraph(graph, PoseGraphOptions{});
  EXPECT_GT(lateral_before, 20.0);
  EXPECT_LT(std::abs(graph.node(n - 1).translation.y()), 1.0);
  EXPECT_LT(RotationErrorDeg(graph.node(n - 1), Rigid3d()), 0.1);
  EXPECT_THROW(graph.AddRegularisationEdge(0, 99, Rigid3d(), covariance), std::invalid_argument);
}

// A chain of 20 nodes 30 mm apart along z (y down) whose steps all read the same pitch of
// 0.02° (the common part of miscalibrated modules): the chain bows. The direction of gravity
// seen from every node (an inclinometer) takes the bow out; what stays is one tilt of the
// whole chain, which the free world direction absorbs.
PoseGraph ChainWithCommonPitch(double direction_sigma_deg) {
  const int n = 20;
  const double pitch = DegToRad(0.02);
  const Rigid3d step(Eigen::Quaterniond(Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX())),
                     Eigen::Vector3d(0.0, 0.0, 30.0));
  PoseGraph graph;
  for (int i = 0; i < n; ++i)
    graph.SetNode(i, Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 30.0 * i)));
  Matrix6d information = Matrix6d::Identity();
  information.diagonal() << 1e4, 1e4, 1e4, Eigen::Vector3d::Constant(std::pow(DegToRad(0.005), -2));
  for (int i = 0; i + 1 < n; ++i) graph.AddEdge({i, i + 1, step, information});
  if (direction_sigma_deg > 0.0) {
    for (int i = 0; i < n; ++i)
      graph.AddDirection({i, Eigen::Vector3d::UnitY(), DegToRad(direction_sigma_deg)});
  }
  return graph;
}

// Largest distance of a node from the straight line through the first and the last.
double Bow(const PoseGraph& graph) {
  const Eigen::Vector3d a = graph.nodes().begin()->second.translation;
  const Eigen::Vector3d b = graph.nodes().rbegin()->second.translation;
  const Eigen::Vector3d axis = (b - a).normalized();
  double bow = 0.0;
  for (const auto& [id, pose] : graph.nodes()) {
    const Eigen::Vector3d d = pose.translation - a;
    bow = std::max(bow, (d - d.dot(axis) * axis).norm());
  }
  return bow;
}

TEST(Optimise, TheDirectionOfGravityFromEveryNodeTakesOutACommonTurn) {
  PoseGraphOptions options;
  options.init = PoseGraphInit::kGiven;
  options.certify = true;
  PoseGraph bowed = ChainWithCommonPitch(0.0);
  ASSERT_TRUE(OptimisePoseGraph(bowed, options).usable);
  // Pitch k · 0.02° at node k: a parabola whose sagitta is 30 mm · 0.02° · 19² / 8.
  EXPECT_NEAR(Bow(bowed), 30.0 * DegToRad(0.02) * 19 * 19 / 8, 0.02);
  PoseGraph held = ChainWithCommonPitch(0.01);
  const PoseGraphReport report = OptimisePoseGraph(held, options);
  ASSERT_TRUE(report.usable);
  EXPECT_LT(Bow(held), 0.1 * Bow(bowed));
  // The chain as a whole may tilt (the steps say it turns 0.38° in all; the directions say it
  // does not turn): the world direction follows the nodes' mean tilt, a rotation about x.
  EXPECT_NEAR(held.world_direction().norm(), 1.0, 1e-12);
  EXPECT_NEAR(held.world_direction().x(), 0.0, 1e-9);
  EXPECT_NEAR(report.final_cost, GraphCost(held), 1e-9);
  EXPECT_FALSE(report.certificate_applicable);
  EXPECT_NE(report.certificate_reason.find("direction"), std::string::npos);
  EXPECT_THROW(held.AddDirection({99, Eigen::Vector3d::UnitY(), 1e-3}), std::invalid_argument);
  EXPECT_THROW(held.AddDirection({0, Eigen::Vector3d::Zero(), 1e-3}), std::invalid_argument);
  EXPECT_THROW(held.AddDirection({0, Eigen::Vector3d::UnitY(), 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
