// Module-pair agreement: the counts per pair of modules, the median offset of the rejected
// registrations at the fused poses, and the rule that flags a pair as contradicting the rig.

#include "sewer3d/register/module_agreement.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace sewer3d {
namespace {

AcquisitionNode Node(int module, int counter) {
  AcquisitionNode n;
  n.module = module;
  n.counter = counter;
  // Cameras 100 mm apart along z, at the identity rotation.
  n.world_from_camera = Rigid3d(Eigen::Quaterniond::Identity(),
                                Eigen::Vector3d(0.0, 0.0, 100.0 * (2 * module + counter)));
  return n;
}

RegistrationEdge Edge(const std::vector<AcquisitionNode>& nodes, int a, int b,
                      RegistrationEdgeType type, double error_mm) {
  RegistrationEdge e;
  e.a = a;
  e.b = b;
  e.type = type;
  e.a_from_b = nodes[a].world_from_camera.Inverse() * nodes[b].world_from_camera;
  e.a_from_b.translation.x() += error_mm;
  return e;
}

class ModuleAgreementTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (int m = 0; m < 3; ++m) {
      for (int c = 0; c < 2; ++c) nodes_.push_back(Node(m, c));
    }
    fused_.world_from_camera.clear();
    for (const AcquisitionNode& n : nodes_) fused_.world_from_camera.push_back(n.world_from_camera);
  }
  void Add(int a, int b, RegistrationEdgeType type, double error_mm, bool accepted) {
    edges_.push_back(Edge(nodes_, a, b, type, error_mm));
    fused_.accepted.push_back(accepted);
    fused_.chi2.push_back(accepted ? 1.0 : 1e6);
  }

  std::vector<AcquisitionNode> nodes_;  // index 2m + c
  std::vector<RegistrationEdge> edges_;
  FusionResult fused_;
};

TEST_F(ModuleAgreementTest, CountsPairwiseEdgesBetweenModulesAndTheRejectedOnesOffsets) {
  using T = RegistrationEdgeType;
  Add(0, 1, T::kFeature, 0.0, true);       // within m0: not a module pair
  Add(1, 2, T::kFeature, 0.1, true);       // m0-m1
  Add(0, 3, T::kProjection, 0.2, true);    // m0-m1
  Add(2, 4, T::kFeature, 80.0, false);     // m1-m2, rejected 80 mm off
  Add(3, 4, T::kFeature, 90.0, false);     // m1-m2, rejected 90 mm off
  Add(3, 5, T::kProjection, 85.0, false);  // m1-m2, rejected 85 mm off
  Add(2, 5, T::kFeature, 0.0, true);       // m1-m2, accepted
  Add(2, 4, T::kRig, 0.0, true);           // a rig edge: not counted
  const std::vector<ModulePairAgreement> pairs = ModulePairAgreements(nodes_, edges_, fused_);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].module_a, 0);
  EXPECT_EQ(pairs[0].module_b, 1);
  EXPECT_EQ(pairs[0].edges, 2);
  EXPECT_EQ(pairs[0].rejected, 0);
  EXPECT_EQ(pairs[0].median_rejected_offset_mm, 0.0);
  EXPECT_FALSE(Disagrees(pairs[0]));
  EXPECT_EQ(pairs[1].module_a, 1);
  EXPECT_EQ(pairs[1].module_b, 2);
  EXPECT_EQ(pairs[1].edges, 4);
  EXPECT_EQ(pairs[1].rejected, 3);
  // The residual's translation is the measurement's error (identity rotations): 80, 85, 90.
  EXPECT_NEAR(pairs[1].median_rejected_offset_mm, 85.0, 1e-9);
  EXPECT_TRUE(Disagrees(pairs[1]));  // 3 of 4 ≥ 75 %
}

TEST_F(ModuleAgreementTest, OneRejectedRegistrationAMinorityOrAFewMillimetresDoNotFlagThePair) {
  ModulePairAgreement p;
  p.edges = 1;
  p.rejected = 1;
  p.median_rejected_offset_mm = 80.0;
  EXPECT_FALSE(Disagrees(p));  // one chance outlier
  p.edges = 10;
  p.rejected = 7;
  EXPECT_FALSE(Disagrees(p));  // 70 % < 75 %
  p.rejected = 8;
  EXPECT_TRUE(Disagrees(p));
  p.median_rejected_offset_mm = 2.0;  // rejected, but only as far off as a sound run's
  EXPECT_FALSE(Disagrees(p));
}

TEST_F(ModuleAgreementTest, AlongThePipeAllModulesCountTogether) {
  using T = RegistrationEdgeType;
  EXPECT_EQ(AlongAgreement(nodes_, edges_, fused_).edges, 0);  // none yet
  Add(0, 1, T::kFeature, 96.0, false);  // m0 along, rejected (odometry 25 x too short)
  Add(2, 3, T::kFeature, 95.0, false);  // m1 along, rejected
  Add(4, 5, T::kFeature, 0.1, true);    // m2 along, accepted
  Add(1, 2, T::kFeature, 0.1, true);    // m0-m1: not along
  const ModulePairAgreement along = AlongAgreement(nodes_, edges_, fused_);
  EXPECT_EQ(along.module_a, -1);
  EXPECT_EQ(along.edges, 3);
  EXPECT_EQ(along.rejected, 2);
  EXPECT_NEAR(along.median_rejected_offset_mm, 96.0, 1e-9);  // of 95 and 96: the upper
  EXPECT_FALSE(Disagrees(along));                            // 2 of 3 < 75 %
  Add(4, 5, T::kProjection, 90.0, false);
  EXPECT_TRUE(Disagrees(AlongAgreement(nodes_, edges_, fused_)));  // 3 of 4
}

TEST_F(ModuleAgreementTest, AFusionOfOtherEdgesIsRefused) {
  Add(1, 2, RegistrationEdgeType::kFeature, 0.0, true);
  fused_.accepted.push_back(true);
  EXPECT_THROW(ModulePairAgreements(nodes_, edges_, fused_), std::invalid_argument);
  fused_.accepted.pop_back();
  fused_.world_from_camera.pop_back();
  EXPECT_THROW(ModulePairAgreements(nodes_, edges_, fused_), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
