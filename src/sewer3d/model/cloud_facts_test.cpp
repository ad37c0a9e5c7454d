#include "sewer3d/model/cloud_facts.hpp"

#include <gtest/gtest.h>

namespace sewer3d {
namespace {

// A 100 × 60 mm patch of wall 300 mm in front of the camera, on a 1 mm grid, scaled.
std::vector<Eigen::Vector3d> Wall(double scale) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 100; ++i) {
    for (int j = 0; j <= 60; ++j)
      points.emplace_back(scale * (i - 50), scale * (j - 30), 300 * scale);
  }
  return points;
}

TEST(CameraCloudFacts, MeasuresExtentDistanceAndPointsBehind) {
  auto points = Wall(1.0);
  points.emplace_back(0.0, 0.0, -10.0);
  points.emplace_back(0.0, 0.0, 0.0);
  const auto facts = DescribeCameraCloud(points);
  EXPECT_EQ(facts.points, 101u * 61u + 2u);
  EXPECT_EQ(facts.behind, 2u);
  EXPECT_NEAR(facts.extent_mm, std::sqrt(100.0 * 100.0 + 60.0 * 60.0 + 310.0 * 310.0), 1e-9);
  // Half the grid lies within 300..~310 mm of the camera centre; the median is close to 300.
  EXPECT_GT(facts.median_distance_mm, 300.0);
  EXPECT_LT(facts.median_distance_mm, 305.0);
  EXPECT_EQ(CloudUnitsProblem(facts), "");
}

TEST(CameraCloudFacts, TellsMetresCentimetresAndMicrometresApart) {
  const auto metres = CloudUnitsProblem(DescribeCameraCloud(Wall(1e-3)));
  EXPECT_NE(metres.find("in metres?"), std::string::npos) << metres;
  const auto centimetres = CloudUnitsProblem(DescribeCameraCloud(Wall(0.05)));
  EXPECT_NE(centimetres.find("in centimetres?"), std::string::npos) << centimetres;
  const auto far = DescribeCameraCloud(Wall(1e3));
  EXPECT_NEAR(far.median_distance_mm, 1e3 * DescribeCameraCloud(Wall(1.0)).median_distance_mm,
              1e-6 * far.median_distance_mm);
  const auto micrometres = CloudUnitsProblem(far);
  EXPECT_NE(micrometres.find("in micrometres?"), std::string::npos) << micrometres;
  EXPECT_NE(micrometres.find("lie 302 m from"), std::string::npos) << micrometres;
  EXPECT_EQ(CloudUnitsProblem(DescribeCameraCloud({})), "");
}

}  // namespace
}  // namespace sewer3d
