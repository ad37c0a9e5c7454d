// model.json of the pipe model (model_io.hpp): written for people and programs alike, so
// besides the numbers it spells out the conventions that turn a pixel into a 3D point.

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/io/model_io.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;
using ojson = nlohmann::ordered_json;

constexpr int kVersion = 1;

ojson Array3(const Eigen::Vector3d& v) { return ojson::array({v.x(), v.y(), v.z()}); }

ojson FileNames(const ModelMapFiles& files, const std::filesystem::path& model_dir) {
  const auto rel = [&](const std::filesystem::path& p) {
    return p.lexically_relative(model_dir).generic_string();
  };
  return {{"texture", rel(files.texture)},
          {"displacement_png", rel(files.displacement_png)},
          {"displacement_tiff", rel(files.displacement_tiff)},
          {"coverage", rel(files.coverage)},
          {"samples", rel(files.samples)},
          {"displacement_view", rel(files.displacement_view)},
          {"surface", rel(files.surface)}};
}

Eigen::Vector3d Vector3(const JsonReader& in, const json& j, const char* key,
                        const std::string& prefix) {
  const std::vector<double> v = in.Numbers(j, key, prefix, 3);
  return {v[0], v[1], v[2]};
}

Centreline ReadCentreline(const JsonReader& in, const json& j, double radius_mm) {
  const std::string prefix = "centreline.";
  Centreline line;
  line.radius_mm = radius_mm;
  line.step_mm = in.Positive(j, "step_mm", prefix);
  const json& samples = in.Array(j, "samples", prefix);
  if (samples.size() < 2) in.Fail(prefix + "samples", "must hold at least 2 samples");
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const std::string at = prefix + "samples[" + std::to_string(k) + "].";
    if (!samples[k].is_object()) in.Fail(at.substr(0, at.size() - 1), "must be an object");
    const double station = in.Number(samples[k], "station_mm", at);
    if (k == 0) line.station0_mm = station;
    const double expected = line.station0_mm + static_cast<double>(k) * line.step_mm;
    if (std::abs(station - expected) > 1e-6 * std::max(1.0, std::abs(expected)))
      in.Fail(at + "station_mm", "must be " + std::to_string(expected) + " (evenly spaced)");
    line.points.push_back(Vector3(in, samples[k], "point_mm", at));
    // Evenly spaced along the pipe: a point far from its neighbour (1e308) is no centreline.
    if (line.points.back().cwiseAbs().maxCoeff() > 1e9 ||
        (k > 0 && (line.points[k] - line.points[k - 1]).norm() > 10.0 * line.step_mm)) {
      in.Fail(at + "point_mm", "lies more than 10 steps (" + std::to_string(line.step_mm) +
                                   " mm each) from the sample before: not a centreline");
    }
    const Eigen::Vector3d crown = Vector3(in, samples[k], "crown", at);
    if (std::abs(crown.norm() - 1.0) > 1e-4) in.Fail(at + "crown", "must be a unit vector");
    line.crowns.push_back(crown);
  }
  return line;
}

}  // namespace

void WriteModelJson(const std::filesystem::path& path, const PipeModelInfo& info) {
  const MapGrid& g = info.grid;
  const std::filesystem::path dir = path.parent_path();
  ojson samples = ojson::array();
  for (std::size_t k = 0; k < info.centreline.points.size(); ++k) {
    samples.push_back({{"station_mm", info.centreline.station0_mm +
                                          static_cast<double>(k) * info.centreline.step_mm},
                       {"point_mm", Array3(info.centreline.points[k])},
                       {"crown", Array3(info.centreline.crowns[k])}});
  }
  ojson tiles = ojson::array();
  for (const ModelTile& t : info.tiles) {
    tiles.push_back({{"index", t.index},
                     {"row0", t.row0},
                     {"rows", t.rows},
                     {"files", FileNames(TileMapFiles(dir, t.index), dir)}});
  }
  ojson j;  // members in the order written, for people reading the file
  j["format"] = "sewer3d pipe model";
  j["version"] = kVersion;
  j["units"] = "mm";
  j["frame"] =
      "model frame: origin at the carrier centre at the run's first image, z along "
      "the pipe, y down, x right";
  j["map"] = {{"resolution_mm", g.resolution_mm},
              {"station0_mm", g.station0_mm},
              {"rows", g.rows},
              {"cols", g.cols},
              {"row", "station_mm = station0_mm + (row + 0.5) * resolution_mm"},
              {"col",
               "clock_rad = (col + 0.5) * 2 pi / cols, 0 at the crown, clockwise "
               "looking downstream (pi/2 = 3 o'clock)"}};
  j["radius_mm"] = info.centreline.radius_mm;
  j["start_station_mm"] = info.start_station_mm;
  j["point"] =
      "p = centreline(station_mm) + (radius_mm + displacement_mm) * (cos(clock_rad) * "
      "crown + sin(clock_rad) * right), right = tangent x crown; centreline and crown "
      "interpolated linearly between samples, tangent along the sampled polyline";
  j["centreline"] = {{"step_mm", info.centreline.step_mm}, {"samples", samples}};
  j["displacement_png"] = {{"scale_mm", info.encoding.scale_mm},
                           {"offset_mm", info.encoding.offset_mm},
                           {"no_data", 0},
                           {"decode", "displacement_mm = offset_mm + value * scale_mm"}};
  j["displacement_tiff"] = "float32 displacement_mm, positive outward, NaN = no data";
  j["displacement_view"] = {{"range_mm", info.view_range_mm},
                            {"colours", "inward blue, 0 white, outward red, no data black"}};
  j["coverage"] = {{"0", "none"}, {"1", "measured"}, {"2", "filled"}};
  j["whole_maps"] = info.whole_maps;
  if (info.whole_maps) j["files"] = FileNames(WholeMapFiles(dir), dir);
  j["tiles"] = tiles;
  WriteTextFileAtomically(path, j.dump(1) + "\n");
}

PipeModelInfo ReadModelJson(const std::filesystem::path& path) {
  const JsonReader in(path);
  const json j = in.ParseObject(ReadTextFile(path));
  if (in.Text(j, "format", "") != "sewer3d pipe model")
    in.Fail("format", "must be \"sewer3d pipe model\"");
  if (in.Integer(j, "version", "", -1) != kVersion)
    in.Fail("version", "must be " + std::to_string(kVersion));
  // Every length in the file is in millimetres; a file that says otherwise is not read as mm.
  if (const std::string units = in.Text(j, "units", "", "mm"); units != "mm")
    in.Fail("units",
            "must be \"mm\" (every length in the file is in millimetres), got \"" + units + "\"");
  PipeModelInfo info;
  const json& map = in.RequiredObject(j, "map", "");
  info.grid.resolution_mm = in.Positive(map, "resolution_mm", "map.");
  // As the model stage makes them: a station far beyond any pipe would make every row's
  // station the same number (and loops over stations endless).
  if (info.grid.resolution_mm < 0.01 || info.grid.resolution_mm > 50.0)
    in.Fail("map.resolution_mm", "must be 0.01 … 50 mm");
  info.grid.station0_mm = in.Number(map, "station0_mm", "map.");
  if (std::abs(info.grid.station0_mm) > 1e9) in.Fail("map.station0_mm", "must be within ±1e9 mm");
  info.grid.rows = in.PositiveSize(map, "rows", "map.");
  info.grid.cols = in.PositiveSize(map, "cols", "map.");
  info.start_station_mm = in.Number(j, "start_station_mm", "");
  if (std::abs(info.start_station_mm) > 1e9) in.Fail("start_station_mm", "must be within ±1e9 mm");
  info.centreline =
      ReadCentreline(in, in.RequiredObject(j, "centreline", ""), in.Positive(j, "radius_mm", ""));
  // The model stage makes cols = round(2 pi radius / resolution): a resolution edited by hand
  // would scale every measurement along the pipe wrongly while the maps stay as they are.
  const double cols = 2.0 * std::numbers::pi * info.centreline.radius_mm / info.grid.resolution_mm;
  if (std::abs(cols - info.grid.cols) > 1.0) {
    in.Fail("map.cols",
            fmt::format("{} columns, but radius_mm {} at resolution_mm {} makes {:.0f}: "
                        "the map's size, radius and resolution disagree",
                        info.grid.cols, info.centreline.radius_mm, info.grid.resolution_mm, cols));
  }
  const json& png = in.RequiredObject(j, "displacement_png", "");
  info.encoding.scale_mm = in.Positive(png, "scale_mm", "displacement_png.");
  info.encoding.offset_mm = in.Number(png, "offset_mm", "displacement_png.");
  info.view_range_mm =
      in.Number(in.Object(j, "displacement_view", ""), "range_mm", "displacement_view.", 10.0);
  info.whole_maps = in.Bool(j, "whole_maps", "", true);
  const json& tiles = in.Array(j, "tiles", "");
  std::vector<int> rows_seen(info.grid.rows, 0);
  for (std::size_t k = 0; k < tiles.size(); ++k) {
    const std::string at = "tiles[" + std::to_string(k) + "].";
    ModelTile t{in.Integer(tiles[k], "index", at, -1), in.Integer(tiles[k], "row0", at, -1),
                in.PositiveSize(tiles[k], "rows", at)};
    if (t.index < 0) in.Fail(at + "index", "must be an integer >= 0");
    if (t.row0 < 0 || t.row0 + t.rows > info.grid.rows)
      in.Fail(at + "row0", "rows must lie within the map's " + std::to_string(info.grid.rows));
    for (int r = t.row0; r < t.row0 + t.rows; ++r) ++rows_seen[r];
    info.tiles.push_back(t);
  }
  if (!info.whole_maps &&
      !std::all_of(rows_seen.begin(), rows_seen.end(), [](int n) { return n == 1; }))
    in.Fail("tiles", "must cover every map row exactly once when whole_maps is false");
  return info;
}

}  // namespace sewer3d
