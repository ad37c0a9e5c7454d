#include "sewer3d/io/pose_checks.hpp"

#include <gtest/gtest.h>

namespace sewer3d {
namespace {

// Two modules, ten acquisitions each, 10 mm of travel along z every 0.5 s.
std::vector<RegistrationPoseRow> SteadyRun() {
  std::vector<RegistrationPoseRow> rows;
  for (int module = 0; module < 2; ++module) {
    for (int counter = 0; counter < 10; ++counter) {
      RegistrationPoseRow row;
      row.module = module;
      row.counter = counter;
      row.time_s = 0.5 * counter;
      row.world_from_camera.translation = Eigen::Vector3d(100.0 * module, 0.0, 10.0 * counter);
      rows.push_back(row);
    }
  }
  return rows;
}

TEST(PoseJumpProblem, AcceptsARunAndRefusesAPoseFarFromItsNeighbours) {
  auto rows = SteadyRun();
  EXPECT_EQ(PoseJumpProblem(rows), "");
  // A stop-and-go run: 1.4 m in 0.5 s is still within 0.5 m + 2 m/s · 0.5 s.
  rows[15].world_from_camera.translation.z() += 1400.0;
  for (int k = 16; k < 20; ++k) rows[k].world_from_camera.translation.z() += 1400.0;
  EXPECT_EQ(PoseJumpProblem(rows), "");
  // One row's z + 1 km (a hand edit in metres where millimetres belong).
  rows = SteadyRun();
  rows[4].world_from_camera.translation.z() += 1e6;
  const std::string problem = PoseJumpProblem(rows);
  EXPECT_NE(problem.find("module 0's acquisitions 3 and 4 lie 1000 m apart, 0.5 s apart"),
            std::string::npos)
      << problem;
  // Rows in any order: each module's are taken in time order.
  std::reverse(rows.begin(), rows.end());
  EXPECT_EQ(PoseJumpProblem(rows), problem);
}

TEST(PoseTravelProblem, ComparesEachModulesTravelWithTheOdometry) {
  std::vector<OdometryReading> odometry;
  for (int k = 0; k <= 50; ++k) odometry.push_back({0.1 * k, 2.0 * k, k + 2});  // 20 mm/s
  auto rows = SteadyRun();  // 90 mm in 4.5 s, as the odometry says
  EXPECT_EQ(PoseTravelProblem(rows, odometry), "");
  for (auto& row : rows) row.world_from_camera.translation /= 1000.0;  // written in metres
  const std::string problem = PoseTravelProblem(rows, odometry);
  EXPECT_NE(problem.find("module 0's camera moves 0.09 mm from acquisition 0 to 9, the odometry "
                         "90 mm"),
            std::string::npos)
      << problem;
  // Without odometry over the acquisitions' times there is nothing to compare.
  EXPECT_EQ(PoseTravelProblem(rows, {}), "");
}

TEST(PoseDirectionProblem, ComparesEachStepsDirectionWithTheOdometry) {
  std::vector<OdometryReading> odometry;
  for (int k = 0; k <= 50; ++k) odometry.push_back({0.1 * k, 2.0 * k, k + 2});  // 20 mm/s
  // The cameras look across the pipe: camera y along the carrier axis (z), as the rig has them.
  const Eigen::Matrix3d looks_up =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  ASSERT_TRUE(looks_up.col(1).isApprox(Eigen::Vector3d::UnitZ()));
  Rig rig;
  rig.modules.resize(2);
  for (RigModule& m : rig.modules)
    m.carrier_from_camera = Rigid3d(looks_up, Eigen::Vector3d::Zero());
  auto rows = SteadyRun();  // 10 mm along z every 0.5 s, as the odometry says
  for (auto& row : rows) row.world_from_camera.rotation = Eigen::Quaterniond(looks_up);
  EXPECT_EQ(PoseDirectionProblem(rows, odometry, rig), "");
  // z negated (another axis convention): every step goes back.
  auto negated = rows;
  for (auto& row : negated) row.world_from_camera.translation.z() *= -1.0;
  const std::string problem = PoseDirectionProblem(negated, odometry, rig);
  EXPECT_NE(problem.find("module 0's camera moves -20 mm along the carrier axis from acquisition "
                         "0 to 2, the odometry 20 mm forward (4 of its 4 steps"),
            std::string::npos)
      << problem;
  // Written as camera_from_world: the rotation inverted, the camera centres too.
  auto inverted = rows;
  for (auto& row : inverted) row.world_from_camera = row.world_from_camera.Inverse();
  EXPECT_NE(PoseDirectionProblem(inverted, odometry, rig), "");
  // A module the rig lacks is left to the model stage's own check; no odometry, no steps.
  EXPECT_EQ(PoseDirectionProblem(negated, odometry, Rig{}), "");
  EXPECT_EQ(PoseDirectionProblem(negated, {}, rig), "");
}

TEST(PoseRigProblem, RefusesAnAcquisitionAwayFromWhereTheOtherModulesPutTheCarrier) {
  std::vector<OdometryReading> odometry;
  for (int k = 0; k <= 50; ++k) odometry.push_back({0.1 * k, 20.0 * k, k + 2});  // 200 mm/s
  // Four modules 100 mm apart along the carrier axis (z), each 80 mm off it, looking out;
  // two trigger groups 20 ms apart, every 0.5 s; the carrier moves 100 mm per 0.5 s along z.
  Rig rig;
  rig.modules.resize(4);
  std::vector<RegistrationPoseRow> rows;
  for (int m = 0; m < 4; ++m) {
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(M_PI / 2 * m, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    rig.modules[m].carrier_from_camera =
        Rigid3d(turn, turn * Eigen::Vector3d(80.0, 0.0, 0.0) + Eigen::Vector3d(0, 0, 100.0 * m));
    for (int counter = 0; counter < 6; ++counter) {
      const double t = 0.5 * counter + 0.02 * (m % 2);
      const Rigid3d world_from_carrier(Eigen::Matrix3d::Identity(),
                                       Eigen::Vector3d(0.0, 0.0, 200.0 * t));
      rows.push_back({m, counter, t, world_from_carrier * rig.modules[m].carrier_from_camera});
    }
  }
  EXPECT_EQ(PoseRigProblem(rows, odometry, rig), "");
  // The registration's few millimetres and a slipping counter (odometry 30 % short) pass.
  auto loose = rows;
  for (std::size_t i = 0; i < loose.size(); ++i)
    loose[i].world_from_camera.translation.x() += (i % 3) * 3.0;
  auto slipping = odometry;
  for (auto& reading : slipping) reading.distance_mm *= 0.7;
  EXPECT_EQ(PoseRigProblem(loose, slipping, rig), "");
  // One pose moved 60 mm along the pipe by hand (module 1, acquisition 3).
  auto moved = rows;
  moved[6 + 3].world_from_camera.translation.z() += 60.0;
  const std::string problem = PoseRigProblem(moved, odometry, rig);
  EXPECT_NE(problem.find("module 1's acquisition 3 puts the carrier 60 mm or more"),
            std::string::npos)
      << problem;
  EXPECT_NE(problem.find("3 of the 3 other modules"), std::string::npos) << problem;
  // The same move, 15 mm: within the registration's slack.
  moved = rows;
  moved[6 + 3].world_from_camera.translation.z() += 15.0;
  EXPECT_EQ(PoseRigProblem(moved, odometry, rig), "");
  // rig.json changed since the registration: module 2 put 100 mm further along the carrier.
  Rig changed = rig;
  changed.modules[2].carrier_from_camera.translation.z() += 100.0;
  EXPECT_NE(PoseRigProblem(rows, odometry, changed).find("module 2's acquisition 0"),
            std::string::npos);
  // Without odometry, 2 m/s over 20 ms (40 mm) is allowed besides the slack: 80 mm still shows.
  moved = rows;
  moved[6 + 3].world_from_camera.translation.z() += 80.0;
  EXPECT_NE(PoseRigProblem(moved, {}, rig), "");
}

}  // namespace
}  // namespace sewer3d
