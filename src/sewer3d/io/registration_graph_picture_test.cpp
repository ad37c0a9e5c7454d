// The registration graph's picture: the crown on the top line, and an edge across 12 o'clock
// drawn where it leaves and re-enters the strip instead of across the whole picture.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "sewer3d/io/registration_io.hpp"

namespace sewer3d {
namespace {

// Pixels of the feature edges' green in a column band of rows [top, bottom).
int GreenPixels(const cv::Mat3b& image, int top, int bottom, int left, int right) {
  int n = 0;
  for (int y = top; y < bottom; ++y)
    for (int x = left; x < right; ++x) {
      const cv::Vec3b& p = image(y, x);
      n += p[1] > 120 && p[0] < 110 && p[2] < 110;
    }
  return n;
}

TEST(RegistrationGraphPicture, AnEdgeAcrossTwelveOClockWrapsAtBothBorders) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "sewer3d_graph_picture_test.png";
  // Stations 0 and 1000 mm span the picture; the edge joins 11 h and 1 h at 500 mm.
  const std::vector<GraphPictureNode> nodes = {
      {0.0, 3.0}, {1000.0, 3.0}, {500.0, 11.0}, {500.0, 13.0}};
  WriteRegistrationGraphPicture(file, nodes, {{2, 3, 0, true}});
  const cv::Mat3b image = cv::imread(file.string(), cv::IMREAD_COLOR);
  std::filesystem::remove(file);
  ASSERT_EQ(image.rows, 700);
  // The strip runs from 12 h (row 100) to 12 h (row 640); the edge's x is the picture's middle.
  const int middle = image.cols / 2;
  EXPECT_GT(GreenPixels(image, 600, 640, middle - 40, middle + 40), 20);  // 11 h → bottom
  EXPECT_GT(GreenPixels(image, 100, 140, middle - 40, middle + 40), 20);  // top → 1 h
  EXPECT_EQ(GreenPixels(image, 200, 540, 0, image.cols), 0);  // nothing across the picture
}

}  // namespace
}  // namespace sewer3d
