// The summary, the map pictures and the 3D viewer (report_sections.hpp).

#include "sewer3d/report/report_sections.hpp"

#include <fmt/core.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "sewer3d/report/assets.hpp"
#include "sewer3d/report/html.hpp"
#include "sewer3d/report/map_images.hpp"
#include "sewer3d/report/viewer_data.hpp"

namespace sewer3d::report {
namespace {

/// The stations (mm) of the first and last preview rows with any coverage; NaN when none.
std::pair<double, double> CoveredStations(const PipeModelInfo& info, const CoarseMaps& preview) {
  int first = -1, last = -1;
  for (int r = 0; r < preview.coverage.rows; ++r) {
    if (cv::sum(preview.coverage.row(r))[0] > 0.0) {
      if (first < 0) first = r;
      last = r;
    }
  }
  if (first < 0) return {NAN, NAN};
  const double cell = info.grid.resolution_mm * preview.row_factor;
  return {info.grid.station0_mm + first * cell,
          std::min(info.grid.station0_mm + (last + 1) * cell,
                   info.grid.station0_mm + info.grid.rows * info.grid.resolution_mm)};
}

std::vector<std::vector<std::string>> ModelFacts(const PipeModelInfo& info,
                                                 const std::optional<CoarseMaps>& preview) {
  const MapGrid& g = info.grid;
  const double end_mm = g.station0_mm + g.rows * g.resolution_mm;
  std::vector<std::vector<std::string>> rows = {
      {"stations of the maps",
       fmt::format("{:.3f} … {:.3f} m", g.station0_mm / 1000.0, end_mm / 1000.0)},
      {"length", fmt::format("{:.3f} m", (end_mm - g.station0_mm) / 1000.0)},
      {"map size", fmt::format("{} stations × {} clock positions ({})", g.rows, g.cols,
                               info.whole_maps ? std::string("whole-run files")
                                               : std::to_string(info.tiles.size()) + " tiles")},
      {"resolution", fmt::format("{} mm", g.resolution_mm)},
      {"model diameter", fmt::format("{:.1f} mm", 2.0 * info.centreline.radius_mm)}};
  if (preview) {
    const auto [s0, s1] = CoveredStations(info, *preview);
    rows.push_back(
        {"stations covered",
         fmt::format("{} … {} m ({:.1f} % of the cells)", html::Fixed(s0 / 1000.0, 3),
                     html::Fixed(s1 / 1000.0, 3), 100.0 * cv::mean(preview->coverage)[0])});
  }
  return rows;
}

}  // namespace

std::string Notes::Add(const std::string& text) {
  list.push_back(text);
  return html::Note(text);
}

std::string SummarySection(const ReportInputs& in, const ModelPictures& model) {
  std::vector<std::vector<std::string>> rows = {{"run folder", in.run_folder}};
  for (const auto& [label, value] : in.run_facts) rows.push_back({label, value});
  if (model.info) {
    for (auto& r : ModelFacts(*model.info, model.preview)) rows.push_back(std::move(r));
  }
  std::string out = "<section id=\"summary\"><h2>Run</h2>\n" + html::Table({"", ""}, rows, "facts");
  if (!in.stages.empty()) {
    std::vector<std::vector<std::string>> stages;
    for (const StageTime& s : in.stages)
      stages.push_back({s.stage, fmt::format("{:.1f}", s.seconds), s.done ? "yes" : "no"});
    out += "<h3>Stages</h3>" + html::Table({"stage", "seconds", "done"}, stages, "figures");
  }
  return out + "</section>\n";
}

std::string MapsSection(const ModelPictures& model, int jpeg_quality, Notes& notes) {
  std::string out = "<section id=\"maps\"><h2>Unrolled maps</h2>\n";
  if (!model.info || !model.preview)
    return out + notes.Add("No map pictures: the model's maps could not be read.") + "</section>\n";
  const CoarseMaps& p = *model.preview;
  const MapGrid& g = model.info->grid;
  const nlohmann::json meta = {
      {"station0_mm", g.station0_mm},
      {"station1_mm", g.station0_mm + p.texture.rows * p.row_factor * g.resolution_mm},
      {"turn_fraction", static_cast<double>(p.texture.cols * p.col_factor) / g.cols},
      {"heat_range_mm", model.heat_range_mm}};
  out +=
      "<p>Station along the pipe to the right (m), clock position down (h: 12 crown, 3 right "
      "looking downstream, 6 invert). Wheel to zoom, drag to pan, double-click to reset; "
      "both maps move together. Pictures " +
      fmt::format("{} × {} px, one pixel {:.2f} mm × {:.2f} mm of wall.</p>\n", p.texture.rows,
                  p.texture.cols, p.row_factor * g.resolution_mm,
                  p.col_factor * 2.0 * M_PI * model.info->centreline.radius_mm / g.cols);
  out += "<script type=\"application/json\" id=\"map-data\">" + html::ScriptJson(meta.dump()) +
         "</script>\n";
  // A texture black wherever the wall was measured was replaced or damaged (a measured wall
  // has light on it): said, and shown as it is.
  int covered = 0, lit = 0;
  for (int r = 0; r < p.texture.rows; ++r) {
    for (int c = 0; c < p.texture.cols; ++c) {
      if (p.coverage(r, c) <= 0.5f) continue;
      ++covered;
      const cv::Vec3b& v = p.texture(r, c);
      lit += v[0] + v[1] + v[2] > 0;
    }
  }
  if (covered > 0 && lit == 0) {
    out += notes.Add(
        "model/texture.png is black wherever coverage.png has the wall measured: replaced or "
        "damaged? (`sewer3d model --force` writes it again)");
  }
  out +=
      "<h3>Texture</h3><div class=\"mapview\"><canvas></canvas><img hidden alt=\"texture\" "
      "src=\"" +
      html::JpegDataUri(StationAlongX(p.texture), jpeg_quality) + "\"></div>\n";
  out +=
      "<h3>Displacement (measured − model radius, outward positive)</h3><div "
      "class=\"mapview\"><canvas></canvas><img hidden alt=\"displacement\" src=\"" +
      html::PngDataUri(StationAlongX(HeatImage(p.displacement_mm, model.heat_range_mm))) +
      "\"></div>\n";
  out += fmt::format(
      "<div class=\"colourbar\"><span>−{0:g} mm (inward)</span><div style=\"background:{1}\">"
      "</div><span>+{0:g} mm (outward)</span><span class=\"nodata\">no data</span></div>\n",
      model.heat_range_mm, HeatGradientCss());
  return out +
         "<p id=\"map-readout\" class=\"readout\">Point at a map to read station and "
         "clock.</p></section>\n";
}

std::string ViewerSection(const ModelPictures& model, Notes& notes) {
  std::string out = "<section id=\"viewer\"><h2>3D viewer</h2>\n";
  if (!model.info || !model.relief || !model.preview)
    return out + notes.Add("No 3D viewer: the model's maps could not be read.") + "</section>\n";
  const std::string_view script = EmbeddedReportAssets().viewer_js;
  if (script.empty())
    return out +
           notes.Add(
               "3D viewer unavailable: this sewer3d was built without three.js "
               "(npm was not reachable when the build was configured).") +
           "</section>\n";
  out +=
      "<div id=\"viewer-wrap\"><canvas id=\"viewer-canvas\"></canvas></div>\n"
      "<div class=\"controls\"><label><input type=\"radio\" name=\"viewer-mode\" "
      "value=\"orbit\" checked> orbit</label> <label><input type=\"radio\" "
      "name=\"viewer-mode\" value=\"fly\"> fly-through</label> <label>station <input "
      "id=\"viewer-station\" type=\"range\" min=\"0\" max=\"1000\" value=\"0\"></label> "
      "<span id=\"viewer-station-text\"></span> <label>relief × <select "
      "id=\"viewer-relief\"><option>1</option><option>3</option><option>10</option>"
      "</select></label></div>\n"
      "<p>Orbit: drag to turn, wheel to zoom, right-drag to pan. Fly-through: the slider or "
      "the arrow keys (↑ ↓ move, ← → turn the view around the pipe) move the camera along "
      "the centreline. Click the wall to read station, clock and radius.</p>\n"
      "<p id=\"viewer-readout\" class=\"readout\">Click the pipe.</p>\n";
  out += "<script type=\"application/json\" id=\"viewer-data\">" +
         html::ScriptJson(ViewerDataJson(*model.info, *model.relief, *model.preview)) +
         "</script>\n<script>" + std::string(script) + "</script>\n";
  return out + "</section>\n";
}

}  // namespace sewer3d::report
