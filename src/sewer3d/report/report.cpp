// WriteReport: one pass over the model's maps (tile by tile when only tiles exist) feeds the map
// pictures, the viewer's relief and the observation crops; then the sections are put together
// and the page is written atomically.

#include "sewer3d/report/report.hpp"

#include <algorithm>
#include <filesystem>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/report/assets.hpp"
#include "sewer3d/report/html.hpp"
#include "sewer3d/report/map_images.hpp"
#include "sewer3d/report/report_sections.hpp"

namespace sewer3d {
namespace {

using report::ModelPictures;

/// The observation's crop clipped to the grid's rows; nullopt when nothing of it is left.
std::optional<MapCrop> ClippedCrop(const MapCrop& crop, const MapGrid& grid) {
  const int row0 = std::max(crop.row0, 0);
  const int row1 = std::min(crop.row0 + crop.rows, grid.rows);
  if (row1 <= row0 || crop.cols <= 0) return std::nullopt;
  return MapCrop{row0, row1 - row0, crop.col0, std::min(crop.cols, grid.cols)};
}

void ReadPictures(const ReportInputs& in, ModelPictures& model) {
  model.info = ReadModelJson(in.model_dir / "model.json");
  const MapGrid& g = model.info->grid;
  const ReportOptions& o = in.options;
  const MapCrop whole{0, g.rows, 0, g.cols};
  MapDownsampler preview(whole, g.cols, DownsampleFactor(g.rows, o.map_station_px),
                         DownsampleFactor(g.cols, o.map_clock_px));
  MapDownsampler relief(whole, g.cols, DownsampleFactor(g.rows, o.viewer_rows),
                        DownsampleFactor(g.cols, o.viewer_clocks));
  std::vector<MapDownsampler*> all = {&preview, &relief};
  const std::vector<Observation> observations =
      in.observations.value_or(std::vector<Observation>{});
  std::vector<std::optional<MapDownsampler>> crops;
  const std::size_t n_crops = std::min(observations.size(), static_cast<std::size_t>(o.max_crops));
  crops.reserve(n_crops);  // `all` points into it: no reallocation
  for (std::size_t i = 0; i < n_crops; ++i) {
    const std::optional<MapCrop> c = ClippedCrop(observations[i].crop, g);
    crops.emplace_back();
    if (!c) continue;
    const int f = DownsampleFactor(std::max(c->rows, c->cols), o.crop_px);
    crops.back().emplace(*c, g.cols, f, f);
    all.push_back(&*crops.back());
  }
  DownsampleModelMaps(in.model_dir, *model.info, all);
  model.preview = preview.Finish();
  model.relief = relief.Finish();
  for (const auto& c : crops) model.crops.push_back(c ? std::optional(c->Finish()) : std::nullopt);
  model.heat_range_mm = model.info->view_range_mm;  // as displacement_view.png, preview.png
}

std::string InlineScript(std::string_view script) {
  std::string out(script);
  for (std::size_t at = out.find("</script"); at != std::string::npos;
       at = out.find("</script", at + 2))
    out.replace(at, 2, "<\\/");
  return "<script>" + out + "</script>\n";
}

std::string Page(const ReportInputs& in, const std::string& notes_html, const std::string& body) {
  const ReportAssets& assets = EmbeddedReportAssets();
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" +
         html::Escape(in.title) + "</title>\n<style>" + std::string(assets.report_css) +
         "</style>\n</head><body>\n<h1>" + html::Escape(in.title) +
         "</h1>\n<nav><a href=\"#summary\">run</a> <a href=\"#maps\">maps</a> <a "
         "href=\"#viewer\">3D</a> <a href=\"#profile\">profile</a> <a "
         "href=\"#observations\">observations</a> <a href=\"#accuracy\">accuracy</a></nav>\n" +
         notes_html + body + InlineScript(assets.report_js) + "</body></html>\n";
}

}  // namespace

void ReportOptions::Check() const {
  ValidatePositive("map_station_px", map_station_px);
  ValidatePositive("map_clock_px", map_clock_px);
  ValidatePositive("viewer_rows", viewer_rows);
  ValidatePositive("viewer_clocks", viewer_clocks);
  ValidatePositive("crop_px", crop_px);
  SEWER3D_VALIDATE(max_crops >= 0, "max_crops", "must be ≥ 0");
  SEWER3D_VALIDATE(jpeg_quality >= 0 && jpeg_quality <= 100, "jpeg_quality", "must be 0 … 100");
}

ReportSummary WriteReport(const ReportInputs& in, const std::filesystem::path& html) {
  in.options.Check();
  ReportSummary summary;
  ModelPictures model;
  report::Notes notes;
  try {
    ReadPictures(in, model);
  } catch (const FileError& e) {
    model = ModelPictures{};
    summary.maps_problem = e.what();
    notes.list.push_back("The model could not be read: " + summary.maps_problem);
  }
  std::string body = report::SummarySection(in, model);
  body += report::MapsSection(model, in.options.jpeg_quality, notes);
  body += report::ViewerSection(model, notes);
  body += report::ProfileSection(in.profile, notes);
  body += report::ObservationsSection(in.observations, model, in.options.jpeg_quality, notes);
  body += report::EvaluationSection(in.evaluations);
  std::string notes_html;
  for (const std::string& n : in.notes) notes_html += html::Note(n);
  if (!summary.maps_problem.empty()) notes_html += html::Note(notes.list.front());
  const std::string page = Page(in, notes_html, body);
  WriteTextFileAtomically(html, page);
  summary.html_bytes = page.size();
  summary.maps = model.preview.has_value();
  summary.viewer = summary.maps && !EmbeddedReportAssets().viewer_js.empty();
  summary.notes = in.notes;
  summary.notes.insert(summary.notes.end(), notes.list.begin(), notes.list.end());
  return summary;
}

}  // namespace sewer3d
