// The rotation form (exactness against the Ceres cost, refusals) and the Riemannian staircase
// (recovery, certificate, lower bound) on synthetic graphs.
#include "sewer3d/posegraph/certificate.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <functional>

#include "sewer3d/posegraph/lifted_cost.hpp"
#include "sewer3d/posegraph/rotation_form.hpp"
#include "sewer3d/posegraph/solver.hpp"
#include "sewer3d/testing/test_graphs.hpp"

namespace sewer3d {
namespace {

using namespace test_graphs;  // NOLINT: the synthetic graphs of this module's tests

/// Isotropic translation information τI (τ in [0.5, 4] / mm²) and a rotation block
/// 100 (I + s·sym(N)) (N standard normal, eigenvalues floored at 5): at s = 0.2 the largest
/// eigenvalue stays below the sum of the other two on almost every edge, at s = 1 it exceeds it
/// on most (DominatedRotationInformation).
Matrix6d IsotropicTranslationInformation(std::mt19937& rng, double s) {
  std::uniform_real_distribution<double> tau(0.5, 4.0);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Matrix3d a;
  for (int i = 0; i < 9; ++i) a(i) = n(rng);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(Eigen::Matrix3d::Identity() +
                                                          0.5 * s * (a + a.transpose()));
  Matrix6d information = Matrix6d::Zero();
  information.topLeftCorner<3, 3>() = tau(rng) * Eigen::Matrix3d::Identity();
  information.bottomRightCorner<3, 3>() = 100.0 * es.eigenvectors() *
                                          es.eigenvalues().cwiseMax(0.05).asDiagonal() *
                                          es.eigenvectors().transpose();
  return information;
}
Matrix6d MildlyAnisotropic(std::mt19937& rng) { return IsotropicTranslationInformation(rng, 0.2); }
Matrix6d StronglyAnisotropic(std::mt19937& rng) {
  return IsotropicTranslationInformation(rng, 1.0);
}

int DominatedEdges(const PoseGraph& graph) {
  int count = 0;
  for (const PoseEdge& e : graph.edges()) {
    const Eigen::Matrix3d omega = e.information.bottomRightCorner<3, 3>();
    count += DominatedRotationInformation(omega) != omega;
  }
  return count;
}

std::vector<Rigid3d> RandomTruth(std::mt19937& rng, int count) {
  std::vector<Rigid3d> truth;
  for (int i = 0; i < count; ++i) truth.push_back(RandomPose(rng, 100.0));
  return truth;
}

Eigen::MatrixXd RotationsOf(const PoseGraph& graph) {
  Eigen::MatrixXd x(3 * graph.nodes().size(), 3);
  int i = 0;
  for (const auto& [id, pose] : graph.nodes())
    x.middleRows<3>(3 * i++) = pose.RotationMatrix().transpose();
  return x;
}

TEST(RotationForm, EqualsTheGraphCostWithTheBestPositions) {
  std::mt19937 rng(11);
  const std::vector<Rigid3d> truth = RandomTruth(rng, 15);
  PoseGraph graph = RingGraph(truth, rng, 0.05, 2.0, StronglyAnisotropic);
  ASSERT_GT(DominatedEdges(graph), 10);
  std::string why;
  const auto form = RotationForm::Build(graph, &why);
  ASSERT_TRUE(form) << why;
  for (int trial = 0; trial < 5; ++trial) {
    for (int id = 0; id < 15; ++id) graph.mutable_node(id) = Perturb(truth[id], rng, 1.0, 50.0);
    const Eigen::MatrixXd x = RotationsOf(graph);
    const double form_cost = form->Cost(x);
    // The form minimises over positions: never above the cost at any positions...
    EXPECT_LE(form_cost, GraphCost(graph) * (1.0 + 1e-12));
    // ...and equal to it at the positions it returns.
    const Eigen::MatrixXd p = form->Positions(x);
    for (int id = 0; id < 15; ++id) {
      graph.mutable_node(id).translation = p.row(id).transpose();
    }
    EXPECT_NEAR(GraphCost(graph), form_cost, 1e-10 * form_cost);
  }
}

TEST(RotationForm, RefusesGraphsWhoseCostIsNotQuadraticInTheRotations) {
  std::mt19937 rng(12);
  const std::vector<Rigid3d> truth = RandomTruth(rng, 8);
  const PoseGraph good = RingGraph(truth, rng, 0.01, 1.0, MildlyAnisotropic);
  std::string why;
  ASSERT_TRUE(RotationForm::Build(good, &why)) << why;
  auto refused = [&](const PoseGraph& graph, const std::string& expected) {
    const bool built = RotationForm::Build(graph, &why).has_value();
    EXPECT_FALSE(built) << expected;
    EXPECT_NE(why.find(expected), std::string::npos) << why;
  };
  PoseGraph anisotropic = good;
  anisotropic.mutable_edges()[2].information(1, 1) *= 1.5;
  refused(anisotropic, "anisotropic translation information");
  PoseGraph coupled = good;
  coupled.mutable_edges()[3].information(0, 4) = coupled.mutable_edges()[3].information(4, 0) = 0.3;
  refused(coupled, "couples translation and rotation");
  PoseGraph robust = good;
  robust.mutable_edges()[0].huber_delta = 1.0;
  refused(robust, "robust loss");
  PoseGraph disconnected = good;
  disconnected.SetNode(99, truth[0]);
  refused(disconnected, "not connected");
  PoseGraph empty;
  empty.SetNode(0, truth[0]);
  refused(empty, "no edges");
  // The dominated form takes any information; the certificate then bounds with it.
  for (const PoseGraph* graph : {&anisotropic, &coupled}) {
    EXPECT_TRUE(RotationForm::Build(*graph, &why, RotationInformation::kDominated)) << why;
    const CertificateReport report = CertifyPoseGraph(*graph, CertificateOptions());
    EXPECT_TRUE(report.applicable) << report.reason;
    EXPECT_TRUE(report.dominated_relaxation);
  }

  PoseGraph two_fixed = good;
  two_fixed.fixed_nodes() = {0, 4};
  const CertificateReport report = CertifyPoseGraph(two_fixed, CertificateOptions());
  EXPECT_FALSE(report.applicable);
  EXPECT_EQ(report.reason, "more than one node is fixed");
  PoseGraphOptions options;
  options.certify = true;
  options.huber_delta = 2.0;
  PoseGraph huber = good;
  const PoseGraphReport lm = OptimisePoseGraph(huber, options);
  EXPECT_FALSE(lm.certificate_applicable);
  EXPECT_EQ(lm.certificate_reason, "robust loss");
}

TEST(RotationForm, DominatedInformationIsBelowTheInformationAndQualifies) {
  std::mt19937 rng(20);
  for (int trial = 0; trial < 200; ++trial) {
    Matrix6d omega = RandomInformation(rng);
    if (trial % 2 == 0)
      omega.topRightCorner<3, 3>().setZero(), omega.bottomLeftCorner<3, 3>().setZero();
    const Matrix6d lowered = DominatedInformation(omega);
    const Eigen::Matrix<double, 6, 1> gap =
        Eigen::SelfAdjointEigenSolver<Matrix6d>(omega - lowered).eigenvalues();
    EXPECT_GT(gap(0), -1e-9 * omega.norm()) << trial;  // Ω − Ω' ⪰ 0: a lower cost everywhere
    EXPECT_EQ((lowered.topRightCorner<3, 3>().norm()), 0.0);
    const double tau = lowered(0, 0);
    EXPECT_GT(tau, 0.0);
    EXPECT_LT((lowered.topLeftCorner<3, 3>() - tau * Eigen::Matrix3d::Identity()).norm(),
              1e-12 * tau);
    const Eigen::Vector3d rotation =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(lowered.bottomRightCorner<3, 3>())
            .eigenvalues();
    EXPECT_GT(rotation(0), 0.0);
    EXPECT_LE(rotation(2), rotation(0) + rotation(1) + 1e-12 * omega.norm());
  }
}

TEST(LiftedCost, GradientAndHessianMatchFiniteDifferencesAlongTheManifold) {
  std::mt19937 rng(16);
  const std::vector<Rigid3d> truth = RandomTruth(rng, 12);
  const PoseGraph graph = RingGraph(truth, rng, 0.1, 5.0, StronglyAnisotropic);
  for (auto information : {RotationInformation::kExact, RotationInformation::kDominated}) {
    const auto form = RotationForm::Build(graph, nullptr, information);
    ASSERT_TRUE(form);
    for (int r : {3, 5}) {
      std::srand(17);
      const Eigen::MatrixXd x =
          lifted::Retract(Eigen::MatrixXd::Zero(36, r), Eigen::MatrixXd::Random(36, r));
      for (int i = 0; i < 36; i += 3) {
        EXPECT_LT(
            (x.middleRows<3>(i) * x.middleRows<3>(i).transpose() - Eigen::Matrix3d::Identity())
                .norm(),
            1e-12);
      }
      const lifted::Point point(*form, x);
      const Eigen::MatrixXd v = lifted::Project(x, Eigen::MatrixXd::Random(36, r));
      EXPECT_LT((lifted::Project(x, v) - v).norm(), 1e-12 * v.norm());  // a projection
      // Central differences along the (second-order) retraction: f' = ⟨grad, v⟩, f'' = ⟨v, Hess v⟩.
      const double t = 1e-4;
      const double plus = form->Cost(lifted::Retract(x, t * v)),
                   minus = form->Cost(lifted::Retract(x, -t * v));
      const double slope = lifted::Inner(point.gradient, v);
      const double curvature = lifted::Inner(v, point.Hessian(*form, v));
      EXPECT_NEAR((plus - minus) / (2 * t), slope, 1e-6 * std::abs(slope)) << r;
      EXPECT_NEAR((plus + minus - 2 * point.cost) / (t * t), curvature, 1e-4 * std::abs(curvature))
          << r;
    }
  }
}

TEST(RotationForm, FactorisationDecidesPositiveDefinitenessOfTheCertificate) {
  std::mt19937 rng(18);
  const std::vector<Rigid3d> truth = RandomTruth(rng, 10);
  const PoseGraph graph = RingGraph(truth, rng, 0.1, 5.0, MildlyAnisotropic);
  const auto form = RotationForm::Build(graph, nullptr);
  ASSERT_TRUE(form);
  std::srand(19);
  const Eigen::MatrixXd x =
      lifted::Retract(Eigen::MatrixXd::Zero(30, 4), Eigen::MatrixXd::Random(30, 4));
  const lifted::Point point(*form, x);
  const Eigen::MatrixXd s =
      lifted::CertificateProduct(*form, point.lambda, Eigen::MatrixXd::Identity(30, 30));
  const Eigen::VectorXd eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (s + s.transpose())).eigenvalues();
  const double lowest = eigenvalues(0), margin = 1e-6 * eigenvalues.cwiseAbs().maxCoeff();
  ASSERT_LT(lowest, -1.0);  // an arbitrary point: S is indefinite
  EXPECT_TRUE(form->IsPositiveDefinite(point.lambda, -lowest + margin));
  EXPECT_FALSE(form->IsPositiveDefinite(point.lambda, -lowest - margin));
}

TEST(Certificate, NoiseFreeRingIsRecoveredFromAFarStartAndCertifiedAtZero) {
  for (auto information : {MildlyAnisotropic, StronglyAnisotropic, RandomInformation}) {
    std::mt19937 rng(13);
    const std::vector<Rigid3d> truth = RandomTruth(rng, 20);
    PoseGraph graph = RingGraph(truth, rng, 0.0, 0.0, information);
    for (int id = 1; id < 20; ++id) graph.mutable_node(id) = Perturb(truth[id], rng, 1.5, 100.0);
    ASSERT_GT(GraphCost(graph), 1e4);
    PoseGraph rounded;
    const CertificateReport report = CertifyPoseGraph(graph, CertificateOptions(), &rounded);
    ASSERT_TRUE(report.applicable) << report.reason;
    EXPECT_TRUE(report.relaxation_solved);
    // Strongly anisotropic rotation information needs the dominated relaxation: the exact
    // one's lifted cost goes negative (about −2.7e3 here); full 6 × 6 information has no
    // exact form at all.
    EXPECT_EQ(report.dominated_relaxation, information != MildlyAnisotropic);
    EXPECT_NEAR(report.lower_bound, 0.0, 1e-6);
    EXPECT_LT(report.rounded_cost, 1e-9);
    EXPECT_LT(GraphCost(rounded), 1e-9);
    // Node 0 (the gauge) kept its true pose, so every pose is the truth, to the staircase's
    // 1e-8 relative gradient tolerance (poses spread over ~100 mm; the weakest directions, with
    // the lowered translation information of full 6 × 6 edges, end ~1e-4 mm off; `--certify`
    // refines with LM after rounding).
    for (int id = 0; id < 20; ++id) {
      EXPECT_LT(RotationErrorDeg(rounded.node(id), truth[id]), 1e-4) << id;
      EXPECT_LT((rounded.node(id).translation - truth[id].translation).norm(), 1e-3) << id;
    }
  }
}

/// Minima LM reaches on `measured` from the truth and from 7 starts with rotations 2 rad off.
std::vector<double> MultiStartMinima(const PoseGraph& measured, const std::vector<Rigid3d>& truth,
                                     std::mt19937& rng) {
  PoseGraphOptions options;
  options.init = PoseGraphInit::kGiven;
  options.function_tolerance = 1e-12;
  std::vector<double> minima;
  for (int start = 0; start < 8; ++start) {
    PoseGraph graph = measured;
    for (size_t id = 1; id < truth.size(); ++id) {
      graph.mutable_node(static_cast<int>(id)) =
          Perturb(truth[id], rng, start == 0 ? 0.0 : 2.0, 50.0);
    }
    const PoseGraphReport lm = OptimisePoseGraph(graph, options);
    EXPECT_TRUE(lm.usable);
    minima.push_back(lm.final_cost);
  }
  return minima;
}

PoseGraphReport Certified(PoseGraph graph) {
  PoseGraphOptions options;
  options.init = PoseGraphInit::kGiven;
  options.function_tolerance = 1e-12;
  options.certify = true;
  return OptimisePoseGraph(graph, options);
}

/// A 30-node ring with 6° (0.1 rad per axis) and 5 mm noise per edge, solved by LM from the
/// truth and 7 far starts, and by LM + certificate; checks that the bound is below every
/// minimum found and that the certified result is no worse than the best of them.
struct RingOutcome {
  double best = 0.0;  ///< lowest LM minimum
  PoseGraphReport report;
};

RingOutcome SolveNoisyRing(unsigned seed,
                           const std::function<Matrix6d(std::mt19937&)>& information) {
  std::mt19937 rng(seed);
  const std::vector<Rigid3d> truth = RandomTruth(rng, 30);
  const PoseGraph measured = RingGraph(truth, rng, 0.1, 5.0, information);
  const std::vector<double> minima = MultiStartMinima(measured, truth, rng);
  RingOutcome outcome;
  outcome.best = *std::min_element(minima.begin(), minima.end());
  outcome.report = Certified(measured);
  EXPECT_TRUE(outcome.report.certificate_applicable) << outcome.report.certificate_reason;
  for (double cost : minima) EXPECT_GE(cost, outcome.report.lower_bound * (1.0 - 1e-9));
  EXPECT_LE(outcome.report.final_cost, outcome.best * (1.0 + 1e-6));
  return outcome;
}

TEST(Certificate, BoundsEveryLocalMinimumAndCertifiesTheBest) {
  const RingOutcome ring = SolveNoisyRing(14, MildlyAnisotropic);
  EXPECT_TRUE(ring.report.relaxation_solved);
  EXPECT_FALSE(ring.report.dominated_relaxation);
  // The relaxation is tight: the best minimum is the global optimum, and LM + certify finds it.
  EXPECT_LE(ring.best - ring.report.lower_bound, 1e-6 * ring.best);
  EXPECT_NEAR(ring.report.final_cost, ring.best, 1e-6 * ring.best);
  EXPECT_LT(ring.report.RelativeGap(), 1e-6);
}

TEST(Certificate, StronglyAnisotropicGraphsGetAValidLooserBound) {
  const RingOutcome ring = SolveNoisyRing(15, StronglyAnisotropic);
  EXPECT_GT(ring.report.dominated_edges, 20);
  // Lowering the information of the dominated edges costs tightness, not validity: here the
  // bound is about a quarter of the best minimum; the exact relaxation's is negative.
  EXPECT_TRUE(ring.report.dominated_relaxation);
  EXPECT_GT(ring.report.lower_bound, 0.2 * ring.best);
}

TEST(Certificate, FullSixBySixInformationGetsAValidBound) {
  // Random information a aᵀ + I: anisotropic translation, coupling, anisotropic rotation.
  const RingOutcome ring = SolveNoisyRing(21, RandomInformation);
  EXPECT_TRUE(ring.report.dominated_relaxation);
  EXPECT_EQ(ring.report.dominated_edges, 39);           // every edge
  EXPECT_GT(ring.report.lower_bound, 0.3 * ring.best);  // 0.584 against 1.2179
}

}  // namespace
}  // namespace sewer3d
