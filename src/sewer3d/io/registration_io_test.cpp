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

}  // namespace
}  // namespace sewer3d
