#include "sewer3d/io/reference_light_io.hpp"

#include <nlohmann/json.hpp>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {

void WriteReferenceLight(const std::filesystem::path& path, const ReferenceLight& r,
                         const std::string& report_json) {
  nlohmann::json log2 = nlohmann::json::array();
  for (const cv::Vec3f& v : r.log2_bgr) log2.push_back({v[0], v[1], v[2]});
  const nlohmann::json j = {{"format", "sewer3d-reference-light"},
                            {"version", 1},
                            {"image_size", {r.image_size.width, r.image_size.height}},
                            {"grid", {r.grid_cols, r.grid_rows}},
                            {"level_bgr", {r.level_bgr[0], r.level_bgr[1], r.level_bgr[2]}},
                            {"log2_bgr", log2},
                            {"geometry",
                             {{"reference_distance_mm", r.geometry.reference_distance_mm},
                              {"normal_step_px", r.geometry.normal_step_px},
                              {"min_cos_incidence", r.geometry.min_cos_incidence}}},
                            {"report", nlohmann::json::parse(report_json)}};
  WriteTextFileAtomically(path, j.dump() + "\n");
}

ReferenceLight ReadReferenceLight(const std::filesystem::path& path) {
  const JsonReader in(path);
  const nlohmann::json j = in.ParseObject(ReadTextFile(path));
  if (in.Text(j, "format", "") != "sewer3d-reference-light")
    in.Fail("format", "must be \"sewer3d-reference-light\"");
  ReferenceLight r;
  const std::vector<double> size = in.Numbers(j, "image_size", "", 2);
  const std::vector<double> grid = in.Numbers(j, "grid", "", 2);
  const std::vector<double> level = in.Numbers(j, "level_bgr", "", 3);
  r.image_size = {static_cast<int>(size[0]), static_cast<int>(size[1])};
  r.grid_cols = static_cast<int>(grid[0]);
  r.grid_rows = static_cast<int>(grid[1]);
  if (r.image_size.width < 1 || r.image_size.height < 1 || r.grid_cols < 1 || r.grid_rows < 1)
    in.Fail("grid", "image and grid sizes must be positive");
  r.level_bgr = {level[0], level[1], level[2]};
  const nlohmann::json& cells = in.Array(j, "log2_bgr", "");
  if (cells.size() != static_cast<size_t>(r.grid_cols) * r.grid_rows)
    in.Fail("log2_bgr", "must hold grid columns x rows cells");
  for (const nlohmann::json& c : cells) {
    if (!c.is_array() || c.size() != 3 || !c[0].is_number() || !c[1].is_number() ||
        !c[2].is_number())
      in.Fail("log2_bgr", "every cell must be 3 numbers");
    r.log2_bgr.emplace_back(c[0].get<float>(), c[1].get<float>(), c[2].get<float>());
  }
  const nlohmann::json& g = in.RequiredObject(j, "geometry", "");
  r.geometry.reference_distance_mm = in.Positive(g, "reference_distance_mm", "geometry.");
  r.geometry.normal_step_px = in.PositiveSize(g, "normal_step_px", "geometry.");
  r.geometry.min_cos_incidence = in.Positive(g, "min_cos_incidence", "geometry.");
  return r;
}

void WriteModuleGains(const std::filesystem::path& path, const ModuleGains& gains) {
  nlohmann::json list = nlohmann::json::array();
  for (const cv::Vec3d& g : gains.gains_bgr) list.push_back({g[0], g[1], g[2]});
  const nlohmann::json j = {
      {"gains_bgr", list}, {"seams", gains.seams}, {"rms_log_residual", gains.rms_log_residual}};
  WriteTextFileAtomically(path, j.dump(2) + "\n");
}

ModuleGains ReadModuleGains(const std::filesystem::path& path, int modules) {
  const JsonReader in(path);
  const nlohmann::json j = in.ParseObject(ReadTextFile(path));
  const nlohmann::json& list = in.Array(j, "gains_bgr", "");
  if (static_cast<int>(list.size()) != modules)
    in.Fail("gains_bgr", "must hold " + std::to_string(modules) + " modules");
  ModuleGains gains;
  for (const nlohmann::json& g : list) {
    if (!g.is_array() || g.size() != 3 || !g[0].is_number() || !g[1].is_number() ||
        !g[2].is_number() || g[0].get<double>() <= 0 || g[1].get<double>() <= 0 ||
        g[2].get<double>() <= 0)
      in.Fail("gains_bgr", "every module's gains must be 3 positive numbers");
    gains.gains_bgr.emplace_back(g[0].get<double>(), g[1].get<double>(), g[2].get<double>());
  }
  gains.seams = in.Integer(j, "seams", "", 0);
  gains.rms_log_residual = in.Number(j, "rms_log_residual", "", 0.0);
  return gains;
}

}  // namespace sewer3d
