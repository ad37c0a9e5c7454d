#include "sewer3d/io/registration_io.hpp"

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

}  // namespace
}  // namespace sewer3d
