// The model folder round trips: the 16-bit displacement code decodes within half a step; a
// model written whole reads back exactly (TIFF, texture, coverage, samples, model.json with
// its centreline); surface.ply has one point per covered cell at radius + displacement; the
// viewable map has its fixed colours; a run written in tiles gives the same files as written
// whole, or keeps only tiles above the size limit and still reads back; bad model.json files
// are FileErrors naming the field.

#include "sewer3d/io/model_io.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/ply_io.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

Centreline Bent() {
  Centreline line;
  line.station0_mm = -20.0;
  line.step_mm = 10.0;
  line.radius_mm = 150.0;
  for (int i = 0; i <= 12; ++i) {
    const double s = line.station0_mm + i * line.step_mm, r = 1500.0;
    line.points.emplace_back(r * (1.0 - std::cos(s / r)), 0.1 * s, r * std::sin(s / r));
    line.crowns.push_back(-Eigen::Vector3d::UnitY());
  }
  return line;
}

// 60 rows × 942 columns at 1 mm; random displacement in ±8 mm, a hole, some filled cells.
PipeMaps RandomMaps() {
  PipeMaps m;
  m.grid = {.resolution_mm = 1.0, .station0_mm = 5.0, .rows = 60, .cols = 942};
  const cv::Size size(m.grid.cols, m.grid.rows);
  m.texture.create(size);
  m.displacement_mm.create(size);
  m.samples.create(size);
  m.coverage = cv::Mat1b(size, static_cast<std::uint8_t>(Coverage::kMeasured));
  cv::RNG rng(7);
  rng.fill(m.texture, cv::RNG::UNIFORM, 0, 256);
  rng.fill(m.displacement_mm, cv::RNG::UNIFORM, -8.0, 8.0);
  rng.fill(m.samples, cv::RNG::UNIFORM, 1, 40);
  m.displacement_mm(cv::Rect(200, 10, 30, 20)).setTo(kNaN);
  m.coverage(cv::Rect(200, 10, 30, 20)).setTo(0);
  m.coverage(cv::Rect(600, 40, 50, 10)).setTo(static_cast<std::uint8_t>(Coverage::kFilled));
  return m;
}

void ExpectSameMaps(const PipeMaps& a, const PipeMaps& b) {
  EXPECT_EQ(cv::norm(a.texture, b.texture, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.samples, b.samples, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.coverage, b.coverage, cv::NORM_INF), 0.0);
  ASSERT_EQ(a.displacement_mm.size(), b.displacement_mm.size());
  for (int r = 0; r < a.grid.rows; ++r) {
    for (int c = 0; c < a.grid.cols; ++c) {
      const float x = a.displacement_mm(r, c), y = b.displacement_mm(r, c);
      ASSERT_TRUE(x == y || (std::isnan(x) && std::isnan(y))) << r << ", " << c;
    }
  }
}

class ModelIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sewer3d_model_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  Centreline line_ = Bent();
  PipeMaps maps_ = RandomMaps();
};

TEST(DisplacementEncoding, RoundTripWithinHalfAStep) {
  const DisplacementEncoding e;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> d(-65.0f, 65.0f);
  for (int i = 0; i < 100000; ++i) {
    const float x = d(rng);
    ASSERT_NEAR(e.Decode(e.Encode(x)), x, e.scale_mm / 2 + 1e-6) << x;
  }
  EXPECT_EQ(e.Encode(0.0f), 32768);
  EXPECT_EQ(e.Encode(kNaN), 0);
  EXPECT_TRUE(std::isnan(e.Decode(0)));
  EXPECT_EQ(e.Encode(-100.0f), 1);  // clipped, never "no data"
  EXPECT_EQ(e.Encode(100.0f), 65535);
}

TEST_F(ModelIoTest, WholeModelReadsBackExactly) {
  const MapFilesReport report = WritePipeModel(dir_, line_, maps_, 1234.5, {});
  const std::size_t covered = 60u * 942u - 600u;
  EXPECT_EQ(report.surface_points, covered);
  EXPECT_EQ(report.clipped_cells, 0u);
  const PipeModel model = ReadPipeModel(dir_);
  ExpectSameMaps(model.maps, maps_);
  const PipeModelInfo& info = model.info;
  EXPECT_EQ(info.grid.rows, 60);
  EXPECT_EQ(info.grid.cols, 942);
  EXPECT_EQ(info.grid.station0_mm, 5.0);
  EXPECT_EQ(info.start_station_mm, 1234.5);
  EXPECT_TRUE(info.whole_maps);
  EXPECT_EQ(info.centreline.radius_mm, 150.0);
  EXPECT_EQ(info.centreline.station0_mm, -20.0);
  ASSERT_EQ(info.centreline.points.size(), line_.points.size());
  for (std::size_t k = 0; k < line_.points.size(); ++k) {
    EXPECT_EQ(info.centreline.points[k], line_.points[k]);
    EXPECT_EQ(info.centreline.crowns[k], line_.crowns[k]);
  }
  EXPECT_EQ(info.encoding.scale_mm, 0.002);
  // The 16-bit PNG decodes within half a step of the float map.
  const cv::Mat1w code = ReadImage(dir_ / "displacement.png", cv::IMREAD_UNCHANGED);
  for (int r = 0; r < 60; ++r) {
    for (int c = 0; c < 942; ++c) {
      const float d = maps_.displacement_mm(r, c);
      if (std::isnan(d)) {
        ASSERT_EQ(code(r, c), 0);
      } else {
        ASSERT_NEAR(info.encoding.Decode(code(r, c)), d, info.encoding.scale_mm / 2 + 1e-6);
      }
    }
  }
  // surface.ply: one point per covered cell, at radius + displacement from the axis.
  const std::vector<Eigen::Vector3d> points = ReadPlyPoints(dir_ / "surface.ply");
  ASSERT_EQ(points.size(), covered);
  const AxisFrame f = info.centreline.FrameAt(info.grid.RowStationMm(0));
  EXPECT_NEAR((points[0] - f.origin).norm(), 150.0 + maps_.displacement_mm(0, 0), 1e-4);
}

TEST_F(ModelIoTest, DisplacementViewHasFixedColours) {
  maps_.displacement_mm(0, 0) = 10.0f;
  maps_.displacement_mm(0, 1) = -25.0f;
  maps_.displacement_mm(0, 2) = 0.0f;
  WritePipeModel(dir_, line_, maps_, 0.0, {});
  const cv::Mat3b view = ReadImage(dir_ / "displacement_view.png", cv::IMREAD_COLOR);
  EXPECT_EQ(view(0, 0), cv::Vec3b(0, 0, 255));  // +10 mm: red (BGR)
  EXPECT_EQ(view(0, 1), cv::Vec3b(255, 0, 0));  // beyond −10 mm: blue
  EXPECT_EQ(view(0, 2), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(view(15, 210), cv::Vec3b(0, 0, 0));  // no data
}

TEST_F(ModelIoTest, TilesGiveTheWholeFilesOrStandForThem) {
  std::vector<ModelTile> tiles;
  for (const auto& [k, row0, rows] : {std::tuple{0, 0, 25}, std::tuple{1, 25, 35}}) {
    PipeMaps tile{maps_.grid, maps_.texture.rowRange(row0, row0 + rows).clone(),
                  maps_.displacement_mm.rowRange(row0, row0 + rows).clone(),
                  maps_.samples.rowRange(row0, row0 + rows).clone(),
                  maps_.coverage.rowRange(row0, row0 + rows).clone()};
    tile.grid.station0_mm += row0 * tile.grid.resolution_mm;
    tile.grid.rows = rows;
    EXPECT_FALSE(ModelTileDone(dir_, k));
    tiles.push_back(WriteModelTile(dir_, k, tile, maps_.grid, line_, {}));
    EXPECT_TRUE(ModelTileDone(dir_, k));
    EXPECT_EQ(tiles.back().row0, row0);
  }
  PipeModelInfo info{line_, maps_.grid, 0.0, {}, 10.0, true, tiles};
  const MapFilesReport whole = FinishTiledModel(dir_, info, {});
  EXPECT_EQ(whole.surface_points, 60u * 942u - 600u);
  ExpectSameMaps(ReadPipeModel(dir_).maps, maps_);
  EXPECT_EQ(ReadPlyPoints(dir_ / "surface.ply").size(), whole.surface_points);

  // Above the size limit: no whole-run files; the tiles are the maps.
  const fs::path tiled = dir_ / "tiled";
  fs::create_directories(tiled);
  fs::copy(dir_ / "tiles", tiled / "tiles", fs::copy_options::recursive);
  ModelFileOptions small;
  small.max_whole_cells = 1000;
  const MapFilesReport none = FinishTiledModel(tiled, info, small);
  EXPECT_EQ(none.surface_points, 0u);
  EXPECT_FALSE(fs::exists(tiled / "texture.png"));
  const PipeModel model = ReadPipeModel(tiled);
  EXPECT_FALSE(model.info.whole_maps);
  ASSERT_EQ(model.info.tiles.size(), 2u);
  EXPECT_EQ(model.info.tiles[1].rows, 35);
  ExpectSameMaps(model.maps, maps_);
  // The headers agree with model.json; a grid of other rows (an edited model.json) is refused
  // before any map is decoded, naming the first map.
  EXPECT_NO_THROW(CheckMapFileSizes(tiled, model.info));
  PipeModelInfo edited = model.info;
  edited.tiles[1].rows = 100;
  try {
    CheckMapFileSizes(tiled, edited);
    ADD_FAILURE() << "no error for a tile of 100 rows";
  } catch (const FileError& e) {
    EXPECT_NE(
        std::string(e.what()).find("tile_1_texture.png: size 942 x 35 is not the map's 942 x 100"),
        std::string::npos)
        << e.what();
  }
}

TEST_F(ModelIoTest, BadModelJsonNamesTheField) {
  WritePipeModel(dir_, line_, maps_, 0.0, {});
  const fs::path path = dir_ / "model.json";
  const std::string good = ReadTextFile(path);
  const auto expect_error = [&](const std::string& from, const std::string& to,
                                const std::string& field) {
    std::string text = good;
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    WriteTextFile(path, text.replace(at, from.size(), to));
    try {
      ReadModelJson(path);
      ADD_FAILURE() << "no error for " << to;
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find(path.string() + ": field '" + field + "'"),
                std::string::npos)
          << e.what();
    }
  };
  expect_error("\"rows\": 60", "\"rows\": -60", "map.rows");
  expect_error("\"station_mm\": -10.0", "\"station_mm\": -9.0", "centreline.samples[1].station_mm");
  expect_error("\"scale_mm\": 0.002", "\"scale_mm\": 0", "displacement_png.scale_mm");
  expect_error("\"version\": 1", "\"version\": 7", "version");
  expect_error("\"units\": \"mm\"", "\"units\": \"m\"", "units");
  expect_error("\"station0_mm\": 5.0", "\"station0_mm\": 1e300", "map.station0_mm");
  expect_error("\"resolution_mm\": 1.0", "\"resolution_mm\": 500", "map.resolution_mm");
  {  // a centreline sample at 1e308 mm: no centreline (inspect ran on it without a word)
    nlohmann::json j = nlohmann::json::parse(good);
    j["centreline"]["samples"][1]["point_mm"][0] = 1e308;
    const std::string text = j.dump(1);
    const auto at = text.find("1e+308");
    ASSERT_NE(at, std::string::npos);
    expect_error(good, text, "centreline.samples[1].point_mm");
  }
  // Edited by hand: measurements along the pipe would be scaled by 2 while the maps stay.
  expect_error("\"resolution_mm\": 1.0", "\"resolution_mm\": 2.0", "map.cols");
}

}  // namespace
}  // namespace sewer3d
