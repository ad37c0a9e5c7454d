#include "sewer3d/pipeline/inspection_crops.hpp"

#include <gtest/gtest.h>

#include <map>
#include <opencv2/core.hpp>

namespace sewer3d {
namespace {

// A 100 mm run of a Ø40 mm pipe at 0.2 mm (500 rows × 628 clock columns): the texture's blue
// channel is the row / 2, the displacement 1 mm, everything measured.
PipeMaps RowCodedMaps(const MapGrid& grid) {
  PipeMaps m;
  m.grid = grid;
  m.texture.create(grid.rows, grid.cols);
  for (int r = 0; r < grid.rows; ++r) m.texture.row(r).setTo(cv::Vec3b(r / 2, 0, 200));
  m.displacement_mm = cv::Mat1f(grid.rows, grid.cols, 1.0F);
  m.samples = cv::Mat1w(grid.rows, grid.cols, 1);
  m.coverage = cv::Mat1b(grid.rows, grid.cols, static_cast<unsigned char>(Coverage::kMeasured));
  return m;
}

PipeMaps Piece(const PipeMaps& whole, int row0, int rows) {
  const cv::Range r(row0, row0 + rows);
  return {whole.grid.Tile(row0, rows), whole.texture.rowRange(r).clone(),
          whole.displacement_mm.rowRange(r).clone(), whole.samples.rowRange(r).clone(),
          whole.coverage.rowRange(r).clone()};
}

TEST(InspectionCrops, EachCropIsHandedOutOnceWhenItsLastTileHasPassed) {
  const MapGrid grid = MakeMapGrid(0.0, 100.0, 20.0, 0.2);
  ASSERT_EQ(grid.rows, 500);
  const PipeMaps whole = RowCodedMaps(grid);
  const std::vector<MapCrop> boxes = {
      {10, 20, 5, 30},     // inside the first tile
      {90, 60, 600, 100},  // across the first two tiles, wrapping around the clock
      {400, 80, 0, 628},   // the whole turn
      {600, 10, 0, 10}};   // beyond the run: clipped, no data
  InspectionCrops crops(boxes, grid, 2.0, 64);
  std::map<std::size_t, cv::Mat3b> images;
  std::map<std::size_t, int> after_tile;
  int tile = 0;
  const InspectionCrops::Done done = [&](std::size_t i, const cv::Mat3b& image) {
    EXPECT_EQ(images.count(i), 0U) << "crop " << i << " handed out twice";
    images[i] = image;
    after_tile[i] = tile;
  };
  for (tile = 0; tile < 5; ++tile) crops.Add(Piece(whole, 100 * tile, 100), done);
  crops.Finish(done);
  ASSERT_EQ(images.size(), 4U);
  EXPECT_EQ(after_tile[0], 0);
  EXPECT_EQ(after_tile[1], 1);
  EXPECT_EQ(after_tile[2], 4);
  // Texture (rows of the crop) above the displacement view, at most 64 px on a side.
  EXPECT_EQ(images[0].size(), cv::Size(30, 40));
  EXPECT_EQ(images[0](0, 0)[0], 5);               // row 10
  EXPECT_EQ(images[0](19, 0)[0], 14);             // row 29
  EXPECT_EQ(images[1].size(), cv::Size(53, 64));  // 120 × 100, area-resampled
  EXPECT_NEAR(images[1](31, 52)[0], 74, 1);       // rows 148, 149: blue 74
  EXPECT_EQ(images[2].size(), cv::Size(64, 16));
  EXPECT_EQ(images[3].size(), cv::Size(10, 2));  // clipped to the last row
}

}  // namespace
}  // namespace sewer3d
