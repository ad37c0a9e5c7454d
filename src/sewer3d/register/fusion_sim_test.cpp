// Fusion of a synthetic registration graph with known truth: an outlier edge is rejected by the
// χ² gate; the straightness prior keeps a straight run straight where the pairwise edges barely
// see the tilt (plastic pipe), and lets a 30 m bend stay bent where they see it (texture).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "sewer3d/register/fusion.hpp"
#include "sewer3d/sim/rig.hpp"
#include "sewer3d/testing/matchers.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kStep = 30.0;  // mm between consecutive acquisitions

Rig OneModuleRig() {
  Rig rig;
  rig.modules.resize(1);  // carrier_from_camera = identity: camera = carrier
  return rig;
}

// Nodes along model z at the odometry's (exact) distances, initial poses straight.
std::vector<AcquisitionNode> StraightNodes(int count) {
  std::vector<AcquisitionNode> nodes(count);
  for (int i = 0; i < count; ++i) {
    nodes[i].counter = i;
    nodes[i].time_s = 0.3 * i;
    nodes[i].distance_mm = kStep * i;
    nodes[i].world_from_camera.translation = Eigen::Vector3d(0, 0, kStep * i);
  }
  return nodes;
}

// σ per residual component (translation mm, rotation rad) → information; a measurement of the
// true relative pose with noise drawn from that covariance.
RegistrationEdge Measured(int a, int b, const std::vector<Rigid3d>& truth, const Vector6d& sigma,
                          RegistrationEdgeType type, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Vector6d noise;
  for (int k = 0; k < 6; ++k) noise[k] = sigma[k] * normal(rng);
  const Rigid3d exact = truth[a].Inverse() * truth[b];
  RegistrationEdge e;
  e.a = a;
  e.b = b;
  e.type = type;
  // Residual r = [p̂ − p ... ] with p̂ = p − noise_t gives r_t = noise_t; q̂ = Exp(noise_r) q.
  e.a_from_b = ApplyUpdate(exact, noise);
  e.information = sigma.cwiseAbs2().cwiseInverse().asDiagonal();
  return e;
}

TEST(Fusion, TheGateRejectsAnOutlierEdgeAndKeepsTheOthers) {
  std::mt19937 rng(7);
  constexpr int kNodes = 20;
  std::vector<AcquisitionNode> nodes = StraightNodes(kNodes);
  std::vector<Rigid3d> truth;
  std::normal_distribution<double> normal;
  for (int i = 0; i < kNodes; ++i) {  // a wandering carrier: ±1 mm, ±0.5°
    const Eigen::Vector3d axis(normal(rng), normal(rng), normal(rng));
    truth.emplace_back(Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * kDeg, axis.normalized())),
                       Eigen::Vector3d(normal(rng), normal(rng), kStep * i));
  }
  nodes[0].world_from_camera = truth[0];  // the gauge
  Vector6d sigma;
  sigma << 0.02, 0.02, 0.02, 0.01 * kDeg, 0.01 * kDeg, 0.01 * kDeg;
  std::vector<RegistrationEdge> edges;
  for (int i = 0; i + 1 < kNodes; ++i) {
    edges.push_back(Measured(i, i + 1, truth, sigma, RegistrationEdgeType::kFeature, rng));
    if (i + 2 < kNodes)
      edges.push_back(Measured(i, i + 2, truth, sigma, RegistrationEdgeType::kFeature, rng));
  }
  const size_t outlier = 10;
  edges[outlier].a_from_b.translation += Eigen::Vector3d(3.0, -2.0, 4.0);  // a wrong match
  for (const RegistrationEdge& e : OdometryEdges(nodes, OneModuleRig(), PriorEdgeOptions{}))
    edges.push_back(e);

  const FusionResult result = FuseRegistration(nodes, edges, FusionOptions{});
  ASSERT_TRUE(result.report.usable);
  EXPECT_EQ(result.report.rejected, 1);
  for (size_t k = 0; k < edges.size(); ++k) EXPECT_EQ(result.accepted[k], k != outlier) << k;
  // Each node within 3σ of the chain's accumulated noise: the turn random-walks by
  // 0.01° / √2 per step (two edges per node), 0.031° after 19 steps; through the lever of the
  // chain (30 mm steps) that is σθ · 30 mm · √(Σ k²) ≈ 0.18 mm at the end.
  for (int i = 0; i < kNodes; ++i)
    EXPECT_THAT(result.world_from_camera[i], testing::PoseNear(truth[i], 0.1, 0.6)) << i;
  const EdgeTypeStatistics& f = result.report.by_type[0];
  EXPECT_EQ(f.edges, 37);
  EXPECT_EQ(f.accepted, 36);
  EXPECT_LT(f.mean_chi2, 12.0);  // χ²(6) minus what the fit absorbs: mean below 6
  EXPECT_TRUE(result.report.final_solve.certificate_applicable)
      << result.report.final_solve.certificate_reason;
}

// A plastic-like chain: the pairwise edges constrain the lateral translation well but the tilt
// only weakly (σ 0.5° per edge), so the tilts' noise random-walks into a bent centreline: the
// end's lateral error is σθ · step · √(Σ k²) ≈ 30 mm over 34 edges of 30 mm. The straightness
// edge over L = 1 m at R = 30 m has σ = L²/2R ⊕ √2 · 2 mm = 17 mm and L/R ⊕ √2 · 0.3° = 2.0°;
// combined, the end's σ is about 1/√(1/30² + 1/17²) ≈ 15 mm: half the drift.
double EndLateralError(bool straightness, std::uint32_t seed) {
  std::mt19937 rng(seed);
  constexpr int kNodes = 35;
  const std::vector<AcquisitionNode> nodes = StraightNodes(kNodes);
  std::vector<Rigid3d> truth;
  for (const AcquisitionNode& n : nodes) truth.push_back(n.world_from_camera);
  Vector6d sigma;
  sigma << 0.02, 0.02, 5.0, 0.5 * kDeg, 0.5 * kDeg, 5.0 * kDeg;
  std::vector<RegistrationEdge> edges;
  for (int i = 0; i + 1 < kNodes; ++i)
    edges.push_back(Measured(i, i + 1, truth, sigma, RegistrationEdgeType::kProjection, rng));
  PriorEdgeOptions priors;
  priors.rig = false;
  priors.straightness = straightness;
  for (const RegistrationEdge& e : PriorEdges(nodes, OneModuleRig(), priors)) edges.push_back(e);
  FusionOptions options;
  options.certify = false;
  const FusionResult result = FuseRegistration(nodes, edges, options);
  EXPECT_TRUE(result.report.usable);
  return result.world_from_camera.back().translation.head<2>().norm();
}

TEST(Fusion, StraightnessKeepsAStraightRunStraight) {
  double with = 0.0, without = 0.0;
  constexpr int kSeeds = 30;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    with += std::pow(EndLateralError(true, seed), 2) / kSeeds;
    without += std::pow(EndLateralError(false, seed), 2) / kSeeds;
  }
  with = std::sqrt(with);
  without = std::sqrt(without);
  RecordProperty("end_lateral_rms_mm", std::to_string(with) + " vs " + std::to_string(without));
  EXPECT_GT(without, 15.0);  // the drift is there: ≈ 30 mm expected
  EXPECT_LT(with, 0.7 * without) << with << " vs " << without;
}

// Textured edges (σ 0.02 mm, 0.01°) along a bend of radius 30 m: the straightness edge's pull
// (1σ at that radius) is small against 34 such edges, so the fitted radius stays within 10 %.
TEST(Fusion, AThirtyMetreBendStaysBent) {
  std::mt19937 rng(11);
  constexpr int kNodes = 35;
  constexpr double kRadius = 30000.0;
  std::vector<AcquisitionNode> nodes = StraightNodes(kNodes);
  std::vector<Rigid3d> truth;
  for (int i = 0; i < kNodes; ++i) {  // the arc turns toward +x (a yaw about −y)
    const double angle = kStep * i / kRadius;
    truth.emplace_back(
        Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY())),
        Eigen::Vector3d(kRadius * (1 - std::cos(angle)), 0, kRadius * std::sin(angle)));
  }
  Vector6d sigma;
  sigma << 0.02, 0.02, 0.02, 0.01 * kDeg, 0.01 * kDeg, 0.01 * kDeg;
  std::vector<RegistrationEdge> edges;
  for (int i = 0; i + 1 < kNodes; ++i)
    edges.push_back(Measured(i, i + 1, truth, sigma, RegistrationEdgeType::kFeature, rng));
  for (const RegistrationEdge& e : PriorEdges(nodes, OneModuleRig(), PriorEdgeOptions{}))
    edges.push_back(e);
  const FusionResult result = FuseRegistration(nodes, edges, FusionOptions{});
  ASSERT_TRUE(result.report.usable);
  const Rigid3d& first = result.world_from_camera.front();
  const Rigid3d& last = result.world_from_camera.back();
  const double turn = first.rotation.angularDistance(last.rotation);
  const double fitted = kStep * (kNodes - 1) / turn;
  RecordProperty("fitted_radius_mm", std::to_string(fitted));
  EXPECT_NEAR(fitted, kRadius, 0.1 * kRadius);
  EXPECT_EQ(result.report.rejected, 0);
}

// One module's chain of 35 acquisitions 30 mm apart, its feature edges (σ 0.02 mm, 0.01°) all
// turned by the same 0.02° of pitch (the common part of the modules' calibration errors that
// the zero sum keeps, docs/registration.md), along a straight pipe or a vertical 30 m bend.
// Returns the fused chain's largest distance from the true poses after aligning the first node
// (the graph's fixed node is at its true pose).
double GravityChainError(bool gravity, double bend_radius_mm, FusionReport& report) {
  std::mt19937 rng(3);
  constexpr int kNodes = 35;
  std::vector<AcquisitionNode> nodes = StraightNodes(kNodes);
  std::vector<Rigid3d> truth;
  for (int i = 0; i < kNodes; ++i) {  // a sag: the pipe turns downward (+y) about x
    const double angle = bend_radius_mm > 0.0 ? kStep * i / bend_radius_mm : 0.0;
    const Eigen::Vector3d at = bend_radius_mm > 0.0
                                   ? Eigen::Vector3d(0, bend_radius_mm * (1 - std::cos(angle)),
                                                     bend_radius_mm * std::sin(angle))
                                   : Eigen::Vector3d(0, 0, kStep * i);
    truth.emplace_back(Eigen::Quaterniond(Eigen::AngleAxisd(-angle, Eigen::Vector3d::UnitX())), at);
    // The inclinometer: the true down in the node's frame, 0.03° of noise per axis.
    std::normal_distribution<double> noise(0.0, 0.03 * kDeg);
    const Eigen::Vector3d tilt(noise(rng), 0.0, noise(rng));
    nodes[i].down_in_camera = Eigen::AngleAxisd(tilt.norm(), tilt.normalized()) *
                              (truth.back().rotation.conjugate() * Eigen::Vector3d::UnitY());
  }
  Vector6d sigma;
  sigma << 0.02, 0.02, 0.02, 0.01 * kDeg, 0.01 * kDeg, 0.01 * kDeg;
  Vector6d common = Vector6d::Zero();
  common[3] = 0.02 * kDeg;
  std::vector<RegistrationEdge> edges;
  for (int i = 0; i + 1 < kNodes; ++i) {
    RegistrationEdge e = Measured(i, i + 1, truth, sigma, RegistrationEdgeType::kFeature, rng);
    e.a_from_b = ApplyUpdate(e.a_from_b, common);
    edges.push_back(e);
  }
  for (const RegistrationEdge& e : PriorEdges(nodes, OneModuleRig(), PriorEdgeOptions{}))
    edges.push_back(e);
  FusionOptions options;
  options.gravity = gravity;
  options.gravity_sigma_deg = 0.03;
  const FusionResult result = FuseRegistration(nodes, edges, options);
  EXPECT_TRUE(result.report.usable);
  report = result.report;
  double worst = 0.0;
  for (int i = 0; i < kNodes; ++i) {
    worst =
        std::max(worst, (result.world_from_camera[i].translation - truth[i].translation).norm());
  }
  return worst;
}

TEST(Fusion, TheInclinometerTakesOutACommonPitchAndKeepsAVerticalBend) {
  FusionReport report;
  // A common pitch of 0.02° per step turns the end by 0.68°: 34 steps bow the chain by
  // 30 · 0.02° · 34² / 2 ≈ 6 mm at its end (less the straightness prior's pull).
  const double bowed = GravityChainError(false, 0.0, report);
  EXPECT_EQ(report.gravity.observations, 0);
  const double held = GravityChainError(true, 0.0, report);
  RecordProperty("straight_mm", std::to_string(held) + " vs " + std::to_string(bowed));
  EXPECT_GT(bowed, 1.0);
  EXPECT_LT(held, 0.1 * bowed) << held << " vs " << bowed;
  EXPECT_EQ(report.gravity.observations, 35);
  EXPECT_LT(report.gravity.rms_deg, 0.06);
  EXPECT_FALSE(report.final_solve.certificate_applicable);
  // A sag of radius 30 m (the end 17 mm lower, turned 1.9°): the inclinometer sees it as the
  // edges do, and it stays.
  const double bend = GravityChainError(true, 30000.0, report);
  RecordProperty("bend_mm", std::to_string(bend));
  EXPECT_LT(bend, 0.1 * bowed) << bend;
}

// 35 acquisitions of one module 30 mm apart whose cable counter reads 0.4 % long (its default
// scale error). The first 20 steps have feature edges (σ 0.02 mm), like concrete; the other 14
// a projection edge blind along the axis (σ 5 mm there), like plastic. Returns the last
// acquisition's error along the pipe.
double ScaledOdometryEndError(bool odometry_scale, FusionReport& report) {
  std::mt19937 rng(7);
  constexpr int kNodes = 35;
  std::vector<AcquisitionNode> nodes = StraightNodes(kNodes);
  std::vector<Rigid3d> truth;
  for (AcquisitionNode& n : nodes) {
    truth.push_back(n.world_from_camera);
    n.distance_mm *= 1.004;
    n.world_from_camera.translation.z() *= 1.004;
  }
  Vector6d textured, blind;
  textured << 0.02, 0.02, 0.02, 0.01 * kDeg, 0.01 * kDeg, 0.01 * kDeg;
  blind << 0.02, 0.02, 5.0, 0.05 * kDeg, 0.05 * kDeg, 5.0 * kDeg;
  std::vector<RegistrationEdge> edges;
  for (int i = 0; i + 1 < kNodes; ++i) {
    const bool seen = i < 20;
    edges.push_back(
        Measured(i, i + 1, truth, seen ? textured : blind,
                 seen ? RegistrationEdgeType::kFeature : RegistrationEdgeType::kProjection, rng));
  }
  for (const RegistrationEdge& e : PriorEdges(nodes, OneModuleRig(), PriorEdgeOptions{}))
    edges.push_back(e);
  FusionOptions options;
  options.odometry_scale = odometry_scale;
  const FusionResult result = FuseRegistration(nodes, edges, options);
  EXPECT_TRUE(result.report.usable);
  report = result.report;
  return result.world_from_camera.back().translation.z() - truth.back().translation.z();
}

TEST(Fusion, TheOdometrysScaleErrorIsTakenWhereTextureSeesTheDistance) {
  FusionReport report;
  // The counter's 0.4 % over the 14 blind steps: 1.7 mm at the end, less what the readings'
  // noise (0.7 mm a step) lets the blind edges and the gate take.
  const double plain = ScaledOdometryEndError(false, report);
  const double scaled = ScaledOdometryEndError(true, report);
  RecordProperty("end_along_error_mm", std::to_string(scaled) + " vs " + std::to_string(plain));
  EXPECT_GT(plain, 0.6 * 0.004 * 14 * kStep);
  EXPECT_LT(std::abs(scaled), 0.3 * plain) << scaled << " vs " << plain;
  // The odometry's group: its bias is the steps' 0.12 mm excess, along the steps only.
  const auto odometry = std::find_if(
      report.biases.begin(), report.biases.end(),
      [](const EdgeGroupBias& b) { return b.type == RegistrationEdgeType::kOdometry; });
  ASSERT_NE(odometry, report.biases.end());
  EXPECT_NEAR(std::abs(odometry->bias.z()), 0.004 * kStep, 0.04);
  EXPECT_LT(odometry->bias.head<2>().norm(), 1e-3);
  EXPECT_LT(odometry->bias.tail<3>().norm(), 1e-6);
}

// A carrier that stands (the counter reads no distance: a stop to look at a defect) gives
// odometry edges of no length: they have no direction for a scale error, so they form no
// scale group, and the fusion stays finite.
TEST(Fusion, ACarrierThatStandsGivesNoScaleGroup) {
  std::mt19937 rng(3);
  std::vector<AcquisitionNode> nodes = StraightNodes(8);
  std::vector<Rigid3d> truth;
  for (AcquisitionNode& n : nodes) {
    n.distance_mm = 0.0;
    n.world_from_camera.translation.setZero();
    truth.push_back(n.world_from_camera);
  }
  Vector6d sigma;
  sigma << 0.02, 0.02, 0.02, 0.01 * kDeg, 0.01 * kDeg, 0.01 * kDeg;
  std::vector<RegistrationEdge> edges;
  for (int i = 0; i + 1 < 8; ++i)
    edges.push_back(Measured(i, i + 1, truth, sigma, RegistrationEdgeType::kFeature, rng));
  for (const RegistrationEdge& e : PriorEdges(nodes, OneModuleRig(), PriorEdgeOptions{}))
    edges.push_back(e);
  const FusionResult result = FuseRegistration(nodes, edges, FusionOptions{});
  EXPECT_TRUE(result.report.usable);
  for (const EdgeGroupBias& b : result.report.biases)
    EXPECT_NE(b.type, RegistrationEdgeType::kOdometry);
  // Seven chained edges of σ 0.02 mm per axis: the last pose within 3σ of the walk,
  // 3 · 0.02 · √(7 · 3) ≈ 0.27 mm.
  for (const Rigid3d& pose : result.world_from_camera) {
    ASSERT_TRUE(pose.translation.allFinite());
    EXPECT_LT(pose.translation.norm(), 0.27);
  }
}

// Two modules of the rig over 15 instants; every registration between them (same counter) errs
// by the same 0.3 mm along the pipe, as a module's calibration error makes it. The rig edges
// know the two cameras' offset only to the carrier's motion between their firings (σ 0.7 mm
// along: odometry), 0.18 mm over the 15 instants; the 15 biased edges (σ 0.15 mm each) would
// win. The group's bias, estimated with the poses (prior σ 0.5 mm), is ≈ 0.3 · 31 / (31 + 4)
// = 0.27 mm, so the fused offset errs by ≈ 0.03 mm instead of ≈ 0.29.
double ModuleOffsetError(bool group_biases, FusionReport& report) {
  std::mt19937 rng(5);
  const Rig rig = MakeRig(testing::SmallDefaultModule(648), RigOptions{});
  constexpr int kInstants = 15;
  std::vector<AcquisitionNode> nodes;
  std::vector<Rigid3d> truth;
  for (int j = 0; j < kInstants; ++j) {
    for (int m = 0; m < 2; ++m) {
      AcquisitionNode n;
      n.module = m;
      n.counter = j;
      n.time_s = 0.5 * j + m * 0.02;
      n.distance_mm = 100.0 * n.time_s;
      n.world_from_camera =
          Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, n.distance_mm)) *
          rig.modules[m].carrier_from_camera;
      truth.push_back(n.world_from_camera);
      nodes.push_back(n);
    }
  }
  Vector6d along_sigma, around_sigma;
  along_sigma << 0.02, 0.02, 0.02, 0.01 * kDeg, 0.01 * kDeg, 0.01 * kDeg;
  around_sigma << 0.15, 0.15, 0.15, 0.04 * kDeg, 0.04 * kDeg, 0.04 * kDeg;
  // The pipe's direction in module 0's camera frame.
  const Eigen::Vector3d along =
      rig.modules[0].carrier_from_camera.rotation.conjugate() * Eigen::Vector3d::UnitZ();
  std::vector<RegistrationEdge> edges;
  for (int j = 0; j < kInstants; ++j) {
    for (int m = 0; m < 2 && j + 1 < kInstants; ++m) {
      edges.push_back(Measured(2 * j + m, 2 * (j + 1) + m, truth, along_sigma,
                               RegistrationEdgeType::kFeature, rng));
    }
    RegistrationEdge around =
        Measured(2 * j, 2 * j + 1, truth, around_sigma, RegistrationEdgeType::kFeature, rng);
    around.a_from_b.translation += 0.3 * along;
    edges.push_back(around);
  }
  for (const RegistrationEdge& e : PriorEdges(nodes, rig, PriorEdgeOptions{})) edges.push_back(e);
  FusionOptions options;
  options.group_biases = group_biases;
  options.odometry_scale = false;  // the feature groups alone (the odometry is exact here)
  options.certify = false;
  const FusionResult result = FuseRegistration(nodes, edges, options);
  EXPECT_TRUE(result.report.usable);
  report = result.report;
  double sum = 0.0;
  for (int j = 0; j < kInstants; ++j) {
    const Rigid3d fused =
        result.world_from_camera[2 * j].Inverse() * result.world_from_camera[2 * j + 1];
    const Rigid3d exact = truth[2 * j].Inverse() * truth[2 * j + 1];
    sum += (fused.translation - exact.translation).dot(along);
  }
  return sum / kInstants;
}

TEST(Fusion, TakesOutABiasSharedByTheRegistrationsOfTwoModules) {
  FusionReport without, with;
  const double before = ModuleOffsetError(false, without);
  const double after = ModuleOffsetError(true, with);
  EXPECT_TRUE(without.biases.empty());
  EXPECT_GT(std::abs(before), 0.2) << before;
  EXPECT_LT(std::abs(after), 0.08) << after;
  // Three groups: each module's along edges (no bias) and the around edges (0.27 expected).
  ASSERT_EQ(with.biases.size(), 3u);
  for (const EdgeGroupBias& b : with.biases) {
    EXPECT_EQ(b.counter_step, b.module_a == b.module_b ? 1 : 0);
    const double expected = b.module_a == b.module_b ? 0.0 : 0.27;
    EXPECT_NEAR(b.bias.head<3>().norm(), expected, 0.05)
        << b.module_a << " " << b.module_b << " " << b.bias.transpose();
    EXPECT_LT(b.bias.tail<3>().norm(), 0.03 * kDeg);  // 3σ of a mean of 15 edges at 0.04°
  }
  RecordProperty("offset_error_mm", std::to_string(before) + " -> " + std::to_string(after));
}

TEST(PriorEdges, RigEdgesFollowTheCarrierAndOddModulesFireLater) {
  const Rig rig = MakeRig(testing::SmallDefaultModule(648), RigOptions{});
  std::vector<AcquisitionNode> nodes;
  for (int j = 0; j < 2; ++j) {
    for (int m = 0; m < 6; ++m) {
      AcquisitionNode n;
      n.module = m;
      n.counter = j;
      n.time_s = 0.5 * j + (m % 2) * 0.02;
      n.distance_mm = 100.0 * n.time_s;
      n.world_from_camera =
          Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, n.distance_mm)) *
          rig.modules[m].carrier_from_camera;
      nodes.push_back(n);
    }
  }
  const std::vector<RegistrationEdge> rig_edges = RigEdges(nodes, rig, PriorEdgeOptions{});
  ASSERT_EQ(rig_edges.size(), 10u);  // a chain of 5 per instant
  for (const RegistrationEdge& e : rig_edges) {
    const Rigid3d expected = nodes[e.a].world_from_camera.Inverse() * nodes[e.b].world_from_camera;
    EXPECT_THAT(e.a_from_b, testing::PoseNear(expected, 1e-9, 1e-9));
    EXPECT_TRUE(IsSymmetricPositiveDefinite(e.information));
  }
  EXPECT_EQ(OdometryEdges(nodes, rig, PriorEdgeOptions{}).size(), 6u);
  EXPECT_EQ(StraightnessEdges(nodes, rig, PriorEdgeOptions{}).size(), 6u);
  // A carrier turn of 1 mrad about its x axis moves camera b (90 mm ahead, 20 ms later: 2 mm
  // more) by the lever; the covariance must carry it: check J against a finite turn.
  const Rigid3d& ca = rig.modules[0].carrier_from_camera;
  const Rigid3d& cb = rig.modules[1].carrier_from_camera;
  const Rigid3d motion(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 2.0));
  Matrix6d cov = Matrix6d::Zero();
  cov(3, 3) = 1.0;  // unit variance about the carrier's x axis
  const Matrix6d c = CameraCovarianceFromCarrier(ca, motion, cb, cov);
  const double h = 1e-6;
  const Rigid3d turned(
      Eigen::Quaterniond(Eigen::AngleAxisd(h, Eigen::Vector3d::UnitX())) * motion.rotation,
      motion.translation);
  PoseEdge reference;
  reference.a_from_b = ca.Inverse() * motion * cb;
  const Vector6d r = EdgeResidual(reference, Rigid3d(), ca.Inverse() * turned * cb) / h;
  EXPECT_TRUE((c - r * r.transpose()).norm() < 1e-4 * c.norm()) << c << "\n" << r.transpose();
}

}  // namespace
}  // namespace sewer3d
