// AlignCameras on cameras whose centres lie on one line, as a carrier's do: the roll about that
// line comes from where the cameras look.

#include "sewer3d/simeval/truth_alignment.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

#include "sewer3d/core/units.hpp"
#include "sewer3d/model/axis_curve.hpp"
#include "sewer3d/simeval/registration_evaluation.hpp"

namespace sewer3d {
namespace {

// Six cameras per station on the z axis, looking outward at clock positions 60° apart, at ten
// stations 67 mm apart: every centre on one line.
std::vector<Rigid3d> CarrierCameras() {
  std::vector<Rigid3d> cameras;
  for (int station = 0; station < 10; ++station) {
    for (int m = 0; m < 6; ++m) {
      const Eigen::Quaterniond clock(
          Eigen::AngleAxisd(DegToRad(60.0 * m), Eigen::Vector3d::UnitZ()));
      const Eigen::Quaterniond outward(Eigen::AngleAxisd(DegToRad(90.0), Eigen::Vector3d::UnitX()));
      cameras.emplace_back(clock * outward, Eigen::Vector3d(0.0, 0.0, 67.0 * station + 15.0 * m));
    }
  }
  return cameras;
}

TEST(AlignCameras, RecoversTheRollAboutACollinearPath) {
  const std::vector<Rigid3d> model = CarrierCameras();
  // The truth: the model rolled 5° about the path, turned a little and moved.
  const Rigid3d truth_from_model(
      Eigen::Quaterniond(Eigen::AngleAxisd(DegToRad(5.0), Eigen::Vector3d::UnitZ()) *
                         Eigen::AngleAxisd(DegToRad(0.5), Eigen::Vector3d::UnitX())),
      Eigen::Vector3d(3.0, -15.0, 300.0));
  std::vector<Rigid3d> world;
  for (const Rigid3d& m : model) world.push_back(truth_from_model * m);
  const Rigid3d found = AlignCameras(model, world);
  EXPECT_LT(found.rotation.angularDistance(truth_from_model.rotation), 1e-9);
  EXPECT_LT((found.translation - truth_from_model.translation).norm(), 1e-6);
}

// A registration that followed an odometry slip: from the sixth station on, the model lies
// 100 mm short of the truth. One alignment splits the difference; the local one holds on each
// side of the slip.
TEST(LocalTruthFromModel, HoldsOnEachSideOfASlip) {
  const std::vector<Rigid3d> model = CarrierCameras();
  TruthAlignment a;
  std::vector<Rigid3d> world;
  a.model_centres.resize(3, static_cast<Eigen::Index>(model.size()));
  for (std::size_t i = 0; i < model.size(); ++i) {
    const int station = static_cast<int>(i / 6), m = static_cast<int>(i % 6);
    Rigid3d w = model[i];
    if (station >= 5) w.translation.z() += 100.0;
    a.poses.push_back({m, station, 0.0, model[i]});
    a.truth[RegistrationVertexId(m, station)] = w;
    a.model_centres.col(static_cast<Eigen::Index>(i)) = model[i].translation;
    world.push_back(w);
  }
  a.truth_from_model = AlignCameras(model, world);
  auto line = ResampleAxis({Eigen::Vector3d(0, 0, -100), Eigen::Vector3d(0, 0, 800)}, 10.0);
  ASSERT_TRUE(line.has_value());
  line->radius_mm = 150.0;
  line->station0_mm = -100.0;
  EXPECT_NEAR(a.truth_from_model.translation.z(), 50.0, 1.0);
  EXPECT_NEAR(LocalTruthFromModel(a, *line, 80.0, 120.0).translation.norm(), 0.0, 1e-6);
  EXPECT_NEAR(LocalTruthFromModel(a, *line, 550.0, 120.0).translation.z(), 100.0, 1e-6);
  // Too few cameras in the window: the whole run's alignment.
  EXPECT_NEAR(LocalTruthFromModel(a, *line, 2000.0, 120.0).translation.z(),
              a.truth_from_model.translation.z(), 1e-12);
}

// The carrier's error per counter (evaluate registration's trajectory_error.svg): the mean of
// its cameras', counters ascending whatever the order of the rows.
TEST(CarrierErrors, AveragesEachCountersCameras) {
  std::vector<NodeError> nodes;
  nodes.push_back({0, 1, {0, 0, 100}, {0.2, 0.4, 0}});
  nodes.push_back({1, 0, {0, 10, 40}, {1.0, 0, 0}});
  nodes.push_back({2, 1, {0, 20, 100}, {0.4, 0.0, 0.3}});
  nodes.push_back({3, 0, {0, -10, 60}, {-1.0, 0, 0.5}});
  const std::vector<CarrierError> carrier = CarrierErrors(nodes);
  ASSERT_EQ(carrier.size(), 2u);
  EXPECT_EQ(carrier[0].counter, 0);
  EXPECT_TRUE(carrier[0].true_centre_mm.isApprox(Eigen::Vector3d(0, 0, 50)));
  EXPECT_TRUE(carrier[0].error_mm.isApprox(Eigen::Vector3d(0, 0, 0.25)));
  EXPECT_EQ(carrier[1].counter, 1);
  EXPECT_TRUE(carrier[1].true_centre_mm.isApprox(Eigen::Vector3d(0, 10, 100)));
  EXPECT_TRUE(carrier[1].error_mm.isApprox(Eigen::Vector3d(0.3, 0.2, 0.15)));
  const std::string svg = TrajectoryErrorSvg(nodes);
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u) << svg.substr(0, 80);
  EXPECT_NE(svg.find("y (down)"), std::string::npos);
}

}  // namespace
}  // namespace sewer3d
