// The profile plots, the observation table with crops and the accuracy figures
// (report_sections.hpp).

#include <fmt/core.h>

#include <opencv2/core.hpp>

#include "sewer3d/report/evaluation_tables.hpp"
#include "sewer3d/report/html.hpp"
#include "sewer3d/report/map_images.hpp"
#include "sewer3d/report/profile_plots.hpp"
#include "sewer3d/report/report_sections.hpp"

namespace sewer3d::report {
namespace {

std::string Quantities(const Observation& o) {
  std::string out;
  for (const Quantity& q : o.quantities) {
    out += q.Measured()
               ? fmt::format("{}{} {:.4g} {}", out.empty() ? "" : "; ", q.name, q.value, q.unit)
               : fmt::format("{}{} not measured", out.empty() ? "" : "; ", q.name);
  }
  return out;
}

/// The crop's texture above its heat map, station along x.
std::string CropImage(const CoarseMaps& crop, double heat_range_mm, int jpeg_quality) {
  const cv::Mat3b texture = StationAlongX(crop.texture);
  const cv::Mat3b heat = StationAlongX(HeatImage(crop.displacement_mm, heat_range_mm));
  cv::Mat3b both(texture.rows * 2 + 2, texture.cols, cv::Vec3b(255, 255, 255));
  texture.copyTo(both.rowRange(0, texture.rows));
  heat.copyTo(both.rowRange(texture.rows + 2, both.rows));
  return "<img class=\"crop\" alt=\"crop\" src=\"" + html::JpegDataUri(both, jpeg_quality) + "\">";
}

std::vector<std::string> ObservationRow(const Observation& o, const std::optional<CoarseMaps>& crop,
                                        double heat_range_mm, int jpeg_quality) {
  return {o.id,
          o.code + o.characterisation,
          html::Fixed(o.station_mm / 1000.0, 2),
          html::Fixed(o.length_mm / 1000.0, 2),
          html::Fixed(o.clock_from_h, 1),
          html::Fixed(o.clock_to_h, 1),
          Quantities(o),
          html::Fixed(o.confidence, 2),
          o.at_joint ? "yes" : "",
          o.remark,
          crop ? CropImage(*crop, heat_range_mm, jpeg_quality) : std::string("–")};
}

}  // namespace

std::string ProfileSection(const std::optional<Profile>& profile, Notes& notes) {
  std::string out = "<section id=\"profile\"><h2>Profile</h2>\n";
  if (!profile)
    return out + notes.Add("No profile (WS/inspection/profile.csv; `sewer3d inspect` makes it).") +
           "</section>\n";
  if (profile->rows.empty())
    return out + notes.Add("The profile has no rows (no section measured well enough).") +
           "</section>\n";
  out += fmt::format(
      "<p>{} cross-sections, nominal diameter {:.1f} mm. Gaps: sections measured "
      "too little.</p>\n",
      profile->rows.size(), profile->nominal_diameter_mm);
  return out + ProfilePlots(*profile) + "</section>\n";
}

std::string ObservationsSection(const std::optional<std::vector<Observation>>& observations,
                                const ModelPictures& model, int jpeg_quality, Notes& notes) {
  std::string out = "<section id=\"observations\"><h2>Observations (EN 13508-2)</h2>\n";
  if (!observations)
    return out +
           notes.Add(
               "No observations (WS/inspection/observations.json; `sewer3d inspect` makes them).") +
           "</section>\n";
  if (observations->empty()) return out + "<p>No observations: nothing found.</p></section>\n";
  if (!model.preview)
    out += notes.Add("Observations shown without crops: no maps.");
  else if (model.crops.size() < observations->size())
    out += notes.Add(fmt::format(
        "Crops shown for the first {} of {} observations (ReportOptions::max_crops keeps the page "
        "and the memory small).",
        model.crops.size(), observations->size()));
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 0; i < observations->size(); ++i) {
    const std::optional<CoarseMaps> none;
    const auto& crop = i < model.crops.size() ? model.crops[i] : none;
    rows.push_back(ObservationRow((*observations)[i], crop, model.heat_range_mm, jpeg_quality));
  }
  out += "<p>Crops: texture above displacement (scale as the maps), station to the right.</p>\n";
  out += html::Table({"id", "code", "station (m)", "length (m)", "clock from (h)", "clock to (h)",
                      "quantities", "confidence", "joint", "remark", "crop"},
                     rows, "observations", /*markup_column=*/10);
  return out + "</section>\n";
}

std::string EvaluationSection(const std::vector<EvaluationText>& evaluations) {
  if (evaluations.empty()) return "";
  std::string out = "<section id=\"accuracy\"><h2>Accuracy against the simulation's truth</h2>\n";
  for (const EvaluationText& e : evaluations) out += EvaluationTables(e.name, e.json);
  return out + "</section>\n";
}

}  // namespace sewer3d::report
