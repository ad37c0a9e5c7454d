#include "sewer3d/io/inspection_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/csv.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;
constexpr int kObservationsVersion = 1;
constexpr const char* kObservationsFormat = "sewer3d-observations";
constexpr const char* kProfileHeader =
    "station_m,coverage,widest_gap_deg,height_mm,width_mm,circumference_mm,mean_diameter_mm,"
    "min_diameter_mm,max_diameter_mm,vertical_change_pct,horizontal_change_pct,ovality_en_pct,"
    "ovality_astm_pct,min_radius_mm,mean_radius_mm,max_radius_mm,nominal_diameter_mm";

/// The measured fields of a row in the order of the header, after station, coverage and gap.
std::vector<double ProfileRow::*> MeasureFields() {
  return {&ProfileRow::height_mm,           &ProfileRow::width_mm,
          &ProfileRow::circumference_mm,    &ProfileRow::mean_diameter_mm,
          &ProfileRow::min_diameter_mm,     &ProfileRow::max_diameter_mm,
          &ProfileRow::vertical_change_pct, &ProfileRow::horizontal_change_pct,
          &ProfileRow::ovality_en_pct,      &ProfileRow::ovality_astm_pct,
          &ProfileRow::min_radius_mm,       &ProfileRow::mean_radius_mm,
          &ProfileRow::max_radius_mm};
}

std::string Field(double x, int decimals) {
  return std::isfinite(x) ? fmt::format("{:.{}f}", x, decimals) : std::string();
}

}  // namespace

InspectionFiles InspectionFilesIn(const std::filesystem::path& workspace) {
  const std::filesystem::path folder = workspace / "inspection";
  return {folder, folder / "profile.csv", folder / "observations.json", folder / "observations.csv",
          folder / "observations.xml"};
}

void WriteProfileCsv(const std::filesystem::path& path, const Profile& profile) {
  std::string text = std::string(kProfileHeader) + "\n";
  for (const ProfileRow& row : profile.rows) {
    text += fmt::format("{:.4f},{:.4f},{:.2f}", row.station_mm / 1000.0, row.coverage,
                        row.widest_gap_deg);
    for (const auto field : MeasureFields()) {
      text += ',';
      text += Field(row.*field, 4);
    }
    text += ',';
    text += Field(profile.nominal_diameter_mm, 3);
    text += '\n';
  }
  WriteTextFileAtomically(path, text);
}

Profile ReadProfileCsv(const std::filesystem::path& path) {
  Profile profile;
  const auto fields = MeasureFields();
  const char* const names[] = {
      "height_mm",       "width_mm",         "circumference_mm",    "mean_diameter_mm",
      "min_diameter_mm", "max_diameter_mm",  "vertical_change_pct", "horizontal_change_pct",
      "ovality_en_pct",  "ovality_astm_pct", "min_radius_mm",       "mean_radius_mm",
      "max_radius_mm"};
  for (const CsvRow& line : ReadCsv(path, kProfileHeader)) {
    ProfileRow row;
    row.station_mm = 1000.0 * CsvNumber(path, line, 0, "station_m");
    row.coverage = CsvNumber(path, line, 1, "coverage");
    row.widest_gap_deg = CsvNumber(path, line, 2, "widest_gap_deg");
    if (row.coverage < 0.0 || row.coverage > 1.0)
      throw FileError(path, fmt::format("line {}: coverage must be in 0..1", line.line));
    if (!profile.rows.empty() && row.station_mm <= profile.rows.back().station_mm)
      throw FileError(path, fmt::format("line {}: station_m must increase", line.line));
    for (size_t i = 0; i < fields.size(); ++i) {
      row.*fields[i] = line.fields[3 + i].empty() ? std::numeric_limits<double>::quiet_NaN()
                                                  : CsvNumber(path, line, 3 + i, names[i]);
    }
    profile.nominal_diameter_mm = CsvNumber(path, line, 16, "nominal_diameter_mm");
    profile.rows.push_back(row);
  }
  return profile;
}

void WriteObservationsJson(const std::filesystem::path& path,
                           const std::vector<Observation>& observations) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const Observation& o : observations) {
    nlohmann::ordered_json quantities = nlohmann::ordered_json::array();
    for (const Quantity& q : o.quantities) {
      const nlohmann::ordered_json value =
          q.Measured() ? nlohmann::ordered_json(q.value) : nlohmann::ordered_json(nullptr);
      quantities.push_back({{"name", q.name}, {"value", value}, {"unit", q.unit}});
    }
    list.push_back({{"id", o.id},
                    {"code", o.code},
                    {"characterisation", o.characterisation},
                    {"station_mm", o.station_mm},
                    {"length_mm", o.length_mm},
                    {"clock_h", o.clock_h},
                    {"clock_from_h", o.clock_from_h},
                    {"clock_to_h", o.clock_to_h},
                    {"at_joint", o.at_joint},
                    {"confidence", o.confidence},
                    {"quantities", quantities},
                    {"crop",
                     {{"row0", o.crop.row0},
                      {"rows", o.crop.rows},
                      {"col0", o.crop.col0},
                      {"cols", o.crop.cols}}},
                    {"remark", o.remark}});
  }
  const nlohmann::ordered_json j = {
      {"format", kObservationsFormat}, {"version", kObservationsVersion}, {"observations", list}};
  WriteTextFileAtomically(path, j.dump(2) + "\n");
}

namespace {

double InRange(const JsonReader& in, const json& j, const char* key, const std::string& prefix,
               double lo, double hi) {
  const double x = in.Number(j, key, prefix);
  if (x < lo || x > hi) in.Fail(prefix + key, fmt::format("must be in {}..{}, got {}", lo, hi, x));
  return x;
}

int NotNegativeInteger(const JsonReader& in, const json& j, const char* key,
                       const std::string& prefix) {
  if (!j.contains(key)) in.Fail(prefix + key, "is missing");
  const int x = in.Integer(j, key, prefix, 0);
  if (x < 0) in.Fail(prefix + key, "must not be negative, got " + std::to_string(x));
  return x;
}

// EN 13508-2's main codes: BAA…BAP (the pipe's structure), BBA…BBH (operation), BCA…BCE
// (inventory), BDA…BDG (other).
bool IsMainCode(const std::string& code) {
  if (code.size() != 3 || code[0] != 'B' || code[1] < 'A' || code[1] > 'D') return false;
  const char last[] = {'P', 'H', 'E', 'G'};
  return code[2] >= 'A' && code[2] <= last[code[1] - 'A'];
}

// Why `characterisation` cannot be that of `code`, or "": EN 13508-2 gives BAJ A (longitudinal),
// B (radial), C (angular) and BAA A (vertical), B (horizontal); any code at most two capitals.
std::string CharacterisationProblem(const std::string& code, const std::string& characterisation) {
  const std::string allowed = code == "BAJ" ? "ABC" : code == "BAA" ? "AB" : "";
  if (!allowed.empty() && !characterisation.empty() &&
      (characterisation.size() != 1 || allowed.find(characterisation[0]) == std::string::npos)) {
    std::string letters;
    for (std::size_t k = 0; k < allowed.size(); ++k)
      letters += (k == 0 ? "" : k + 1 == allowed.size() ? " or " : ", ") + allowed.substr(k, 1);
    return "'" + characterisation + "' is not a characterisation of " + code + " (" + letters + ")";
  }
  const bool capitals = std::all_of(characterisation.begin(), characterisation.end(),
                                    [](char c) { return c >= 'A' && c <= 'Z'; });
  if (characterisation.size() > 2 || !capitals)
    return "'" + characterisation + "' is not an EN 13508-2 characterisation (1 or 2 capitals)";
  return "";
}

// The unit a quantity's name implies (offset_mm: mm), or "" for a name without a known suffix.
std::string UnitOfName(const std::string& name) {
  constexpr std::pair<const char*, const char*> kSuffixes[] = {{"_mm", "mm"},   {"_mm2", "mm2"},
                                                               {"_pct", "%"},   {"_pct_of_dn", "%"},
                                                               {"_deg", "deg"}, {"_h", "h"}};
  for (const auto& [suffix, unit] : kSuffixes) {
    if (name.ends_with(suffix)) return unit;
  }
  return "";
}

Observation ReadObservation(const JsonReader& in, const json& j, const std::string& p) {
  if (!j.is_object()) in.Fail(p.substr(0, p.size() - 1), "must be an object");
  in.OnlyKnown(
      j, p,
      {"id", "code", "characterisation", "station_mm", "length_mm", "clock_h", "clock_from_h",
       "clock_to_h", "at_joint", "confidence", "quantities", "crop", "remark"});
  Observation o;
  o.id = in.Text(j, "id", p);
  o.code = in.Text(j, "code", p);
  if (!IsMainCode(o.code)) {
    in.Fail(p + "code",
            "'" + o.code + "' is not an EN 13508-2 main code (BAA-BAP, BBA-BBH, BCA-BCE, BDA-BDG)");
  }
  o.characterisation = in.Text(j, "characterisation", p, "");
  if (const std::string problem = CharacterisationProblem(o.code, o.characterisation);
      !problem.empty()) {
    in.Fail(p + "characterisation", problem);
  }
  o.station_mm = InRange(in, j, "station_mm", p, -1e9, 1e9);  // as model.json's stations
  o.length_mm = InRange(in, j, "length_mm", p, 0.0, 1e9);
  o.clock_h = InRange(in, j, "clock_h", p, 0.0, 12.0);
  o.clock_from_h = InRange(in, j, "clock_from_h", p, 0.0, 12.0);
  o.clock_to_h = InRange(in, j, "clock_to_h", p, 0.0, 12.0);
  if (!j.contains("at_joint")) in.Fail(p + "at_joint", "is missing");
  o.at_joint = in.Bool(j, "at_joint", p, false);
  o.confidence = InRange(in, j, "confidence", p, 0.0, 1.0);
  const json& quantities = in.Array(j, "quantities", p);
  for (size_t i = 0; i < quantities.size(); ++i) {
    const std::string q = p + "quantities[" + std::to_string(i) + "].";
    if (!quantities[i].is_object()) in.Fail(q.substr(0, q.size() - 1), "must be an object");
    in.OnlyKnown(quantities[i], q, {"name", "value", "unit"});
    // null: not measured (Quantity).
    const bool measured = !(quantities[i].contains("value") && quantities[i]["value"].is_null());
    o.quantities.push_back(
        {in.Text(quantities[i], "name", q),
         measured ? in.Number(quantities[i], "value", q) : std::numeric_limits<double>::quiet_NaN(),
         in.Text(quantities[i], "unit", q, "")});
    const Quantity& read = o.quantities.back();
    const std::string implied = UnitOfName(read.name);
    if (!implied.empty() && !read.unit.empty() && read.unit != implied) {
      in.Fail(q + "unit", "'" + read.unit + "' contradicts the quantity's name " + read.name +
                              " (" + implied + ")");
    }
  }
  const json& crop = in.RequiredObject(j, "crop", p);
  const std::string c = p + "crop.";
  in.OnlyKnown(crop, c, {"row0", "rows", "col0", "cols"});
  o.crop = {NotNegativeInteger(in, crop, "row0", c), NotNegativeInteger(in, crop, "rows", c),
            NotNegativeInteger(in, crop, "col0", c), NotNegativeInteger(in, crop, "cols", c)};
  o.remark = in.Text(j, "remark", p, "");
  return o;
}

}  // namespace

std::vector<Observation> ReadObservationsJson(const std::filesystem::path& path) {
  const JsonReader in(path);
  const json j = in.ParseObject(ReadTextFile(path));
  in.OnlyKnown(j, "", {"format", "version", "observations"});
  if (in.Text(j, "format", "", "") != kObservationsFormat)
    in.Fail("format", std::string("must be \"") + kObservationsFormat + "\"");
  if (in.Integer(j, "version", "", -1) != kObservationsVersion)
    in.Fail("version", "must be " + std::to_string(kObservationsVersion));
  if (!j.contains("observations")) in.Fail("observations", "is missing");
  const json& list = in.Array(j, "observations", "");
  std::vector<Observation> observations;
  std::set<std::string> ids;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string p = "observations[" + std::to_string(i) + "].";
    observations.push_back(ReadObservation(in, list[i], p));
    if (!ids.insert(observations.back().id).second)
      in.Fail(p + "id", "'" + observations.back().id + "' is listed twice");
  }
  return observations;
}

}  // namespace sewer3d
