#include "sewer3d/report/report.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "sewer3d/io/model_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/report/assets.hpp"
#include "sewer3d/report/evaluation_tables.hpp"
#include "sewer3d/report/html.hpp"
#include "sewer3d/report/map_images.hpp"
#include "sewer3d/report/test_model.hpp"
#include "sewer3d/report/viewer_data.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;
using testing_report::KnownBump;

class ReportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sewer3d_report_test_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    grid_ = MakeMapGrid(0.0, 200.0, kRadius, 1.0);
    centreline_ = testing_report::StraightCentreline(0.0, 200.0, kRadius);
    maps_ = testing_report::BumpMaps(grid_, kRadius, bump_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  ReportInputs Inputs() const {
    ReportInputs in;
    in.model_dir = dir_ / "model";
    in.run_folder = "/runs/test";
    in.profile = testing_report::OvalProfile(5.0, 195.0, kRadius);
    in.observations = std::vector<Observation>{testing_report::BumpObservation(grid_, bump_)};
    in.evaluations = {{"model", R"({"all": {"rms_mm": 0.05}})"}};
    return in;
  }
  ReportSummary Write(const ReportInputs& in, std::string& html) const {
    ReportSummary s = WriteReport(in, dir_ / "report" / "index.html");
    html = ReadTextFile(dir_ / "report" / "index.html");
    EXPECT_EQ(s.html_bytes, html.size());
    return s;
  }
  static bool ViewerUnavailableOnly(const std::vector<std::string>& notes) {
    for (const std::string& n : notes) {
      if (n.find("3D viewer unavailable") == std::string::npos) return false;
    }
    return notes.size() <= 1 && EmbeddedReportAssets().viewer_js.empty() == (notes.size() == 1);
  }

  static constexpr double kRadius = 150.0;
  fs::path dir_;
  MapGrid grid_;
  Centreline centreline_;
  KnownBump bump_;
  PipeMaps maps_;
};

TEST_F(ReportTest, WholeModelGivesEverySectionSelfContained) {
  WritePipeModel(dir_ / "model", centreline_, maps_, 0.0, ModelFileOptions{});
  std::string html;
  const ReportSummary s = Write(Inputs(), html);
  EXPECT_TRUE(s.maps);
  EXPECT_TRUE(s.maps_problem.empty());
  EXPECT_TRUE(ViewerUnavailableOnly(s.notes));
  for (const char* part : {"id=\"maps\"", "data:image/jpeg;base64,", "id=\"viewer\"",
                           "<svg class=\"plot\"", "class=\"crop\"", "<td>BAF</td>", "<td>0.12</td>",
                           "all / rms_mm", "200 stations × 942 clock"}) {
    EXPECT_NE(html.find(part), std::string::npos) << part;
  }
  for (const char* remote : {"src=\"http", "href=\"http", "src=\"//", "url(http"})
    EXPECT_EQ(html.find(remote), std::string::npos) << remote;
  EXPECT_EQ(html.find("<script src"), std::string::npos);
}

TEST_F(ReportTest, CropsStopAtTheLimitWithANote) {
  WritePipeModel(dir_ / "model", centreline_, maps_, 0.0, ModelFileOptions{});
  ReportInputs in = Inputs();
  in.observations->resize(5, in.observations->front());
  in.options.max_crops = 2;
  std::string html;
  const ReportSummary s = Write(in, html);
  std::size_t crops = 0;
  for (std::size_t at = html.find("class=\"crop\""); at != std::string::npos;
       at = html.find("class=\"crop\"", at + 1))
    ++crops;
  EXPECT_EQ(crops, 2U);
  bool noted = false;
  for (const std::string& n : s.notes)
    noted |= n.find("first 2 of 5 observations") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST_F(ReportTest, TiledModelIsDownsampledTileByTile) {
  ModelFileOptions options;
  options.max_whole_cells = 1;  // keep only the tiles
  PipeModelInfo info{centreline_, grid_, 0.0, options.encoding, 10.0, false, {}};
  for (int k = 0; k < 2; ++k) {
    PipeMaps tile;
    tile.grid = grid_.Tile(100 * k, 100);
    const cv::Range rows(100 * k, 100 * k + 100);
    tile.texture = maps_.texture.rowRange(rows).clone();
    tile.displacement_mm = maps_.displacement_mm.rowRange(rows).clone();
    tile.samples = maps_.samples.rowRange(rows).clone();
    tile.coverage = maps_.coverage.rowRange(rows).clone();
    info.tiles.push_back(WriteModelTile(dir_ / "model", k, tile, grid_, centreline_, options));
  }
  FinishTiledModel(dir_ / "model", info, options);
  ASSERT_FALSE(ReadModelJson(dir_ / "model" / "model.json").whole_maps);
  std::string html;
  const ReportSummary s = Write(Inputs(), html);
  EXPECT_TRUE(s.maps) << s.maps_problem;
  EXPECT_NE(html.find("(2 tiles)"), std::string::npos);
}

TEST_F(ReportTest, MissingModelStillGivesAReportWithANote) {
  std::string html;
  const ReportSummary s = Write(Inputs(), html);
  EXPECT_FALSE(s.maps);
  EXPECT_FALSE(s.viewer);
  EXPECT_NE(s.maps_problem.find("model.json"), std::string::npos) << s.maps_problem;
  EXPECT_NE(html.find("The model could not be read"), std::string::npos);
  EXPECT_NE(html.find("<td>BAF</td>"), std::string::npos);  // observations without crops
  EXPECT_NE(html.find("<svg class=\"plot\""), std::string::npos);
}

TEST_F(ReportTest, OlderModelVersionAndMissingMapAreNamed) {
  WritePipeModel(dir_ / "model", centreline_, maps_, 0.0, ModelFileOptions{});
  fs::remove(dir_ / "model" / "texture.png");
  std::string html;
  EXPECT_NE(Write(Inputs(), html).maps_problem.find("texture.png"), std::string::npos);
  nlohmann::json j = nlohmann::json::parse(ReadTextFile(dir_ / "model" / "model.json"));
  j["version"] = 0;
  WriteTextFile(dir_ / "model" / "model.json", j.dump());
  const ReportSummary s = Write(Inputs(), html);
  EXPECT_NE(s.maps_problem.find("version"), std::string::npos) << s.maps_problem;
  EXPECT_NE(html.find("id=\"summary\""), std::string::npos);
}

// A texture.png replaced by a black image of its size is read (the sizes agree) but is no
// measured wall: noted. The model of WholeModelGivesEverySectionSelfContained has no such note.
TEST_F(ReportTest, ABlackTextureIsNoted) {
  WritePipeModel(dir_ / "model", centreline_, maps_, 0.0, ModelFileOptions{});
  const cv::Mat texture = cv::imread((dir_ / "model" / "texture.png").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(texture.empty());
  cv::imwrite((dir_ / "model" / "texture.png").string(), cv::Mat3b::zeros(texture.size()));
  std::string html;
  const ReportSummary s = Write(Inputs(), html);
  EXPECT_TRUE(s.maps);
  int noted = 0;
  for (const std::string& n : s.notes) noted += n.find("texture.png is black") != std::string::npos;
  EXPECT_EQ(noted, 1);
}

TEST_F(ReportTest, MissingObservationsAndProfileAreNoted) {
  WritePipeModel(dir_ / "model", centreline_, maps_, 0.0, ModelFileOptions{});
  ReportInputs in = Inputs();
  in.profile.reset();
  in.observations.reset();
  std::string html;
  const ReportSummary s = Write(in, html);
  EXPECT_TRUE(s.maps);
  int noted = 0;
  for (const std::string& n : s.notes) {
    noted += n.rfind("No observations", 0) == 0 || n.rfind("No profile", 0) == 0;
    EXPECT_NE(html.find(html::Escape(n)), std::string::npos) << n;
  }
  EXPECT_EQ(noted, 2);
}

TEST_F(ReportTest, ViewerDataPutsTheBumpWhereItIs) {
  const MapCrop whole{0, grid_.rows, 0, grid_.cols};
  MapDownsampler relief(whole, grid_.cols, 2, 4), texture(whole, grid_.cols, 1, 1);
  relief.Add(maps_, 0);
  texture.Add(maps_, 0);
  PipeModelInfo info;
  info.centreline = centreline_;
  info.grid = grid_;
  const nlohmann::json j =
      nlohmann::json::parse(ViewerDataJson(info, relief.Finish(), texture.Finish()));
  ASSERT_EQ(j["rows"], 100);
  ASSERT_EQ(j["clocks"], 236);  // ceil(942 / 4)
  std::string bytes;            // decode the base64 int16 grid
  const std::string b64 = j["displacement_b64"];
  const std::string digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (std::size_t i = 0; i + 3 < b64.size(); i += 4) {
    unsigned v = 0;
    for (int k = 0; k < 4; ++k) v = v << 6U | (b64[i + k] == '=' ? 0 : digits.find(b64[i + k]));
    bytes += {static_cast<char>(v >> 16U), static_cast<char>(v >> 8U), static_cast<char>(v)};
  }
  double best = -1e9;
  int best_row = 0, best_col = 0;
  for (int r = 0; r < 100; ++r) {
    for (int c = 0; c < 236; ++c) {
      const std::size_t k = 2 * (static_cast<std::size_t>(r) * 236 + c);
      const auto v = static_cast<std::int16_t>(static_cast<unsigned char>(bytes[k]) |
                                               static_cast<unsigned char>(bytes[k + 1]) << 8U);
      if (v != -32768 && v / 100.0 > best) best = v / 100.0, best_row = r, best_col = c;
    }
  }
  EXPECT_NEAR(best, bump_.height_mm, 0.01);
  EXPECT_NEAR(j["stations_mm"][best_row].get<double>(), bump_.station_mm, 9.0);  // on the plateau
  EXPECT_NEAR(j["clocks_rad"][best_col].get<double>() / (2 * M_PI) * 12, bump_.clock_h,
              9.0 / 150 * 12 / (2 * M_PI));
  EXPECT_NEAR(j["frames"][9 * best_row + 2].get<double>(), j["stations_mm"][best_row].get<double>(),
              1e-9);
}

TEST(ReportPieces, HeatScaleBase64AndEvaluationTables) {
  EXPECT_EQ(HeatColour(0.0), cv::Vec3b(246, 246, 246));
  EXPECT_GT(HeatColour(-1.0)[0], HeatColour(-1.0)[2]);  // inward blue (BGR)
  EXPECT_GT(HeatColour(1.0)[2], HeatColour(1.0)[0]);    // outward red
  EXPECT_EQ(html::Base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(html::Base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(html::Base64("f"), "Zg==");
  const std::string t = EvaluationTables("model", R"({"a": {"b": 1.23456}, "rows": [{"h": 1}]})");
  EXPECT_NE(t.find("<td>a / b</td><td>1.235</td>"), std::string::npos) << t;
  EXPECT_NE(t.find("<h4>rows</h4>"), std::string::npos);
  EXPECT_NE(EvaluationTables("x", "not json").find("class=\"note\""), std::string::npos);
}

TEST(ReportPieces, TableCellsFromFilesNeverBecomeMarkup) {
  // A remark read from observations.json that starts like markup stays text; only the
  // column made of markup is written as it is.
  const std::string t =
      html::Table({"remark", "crop"}, {{"</td><script>alert(1)</script>", "<img alt=\"crop\">"}},
                  "", /*markup_column=*/1);
  EXPECT_EQ(t.find("<script>"), std::string::npos) << t;
  EXPECT_NE(t.find("&lt;/td&gt;&lt;script&gt;"), std::string::npos) << t;
  EXPECT_NE(t.find("<td><img alt=\"crop\"></td>"), std::string::npos) << t;
}

}  // namespace
}  // namespace sewer3d
