#pragma once
/// \file
/// The inspection's files (WS/inspection/, docs/inspection.md "Files"):
///
/// - `profile.csv`: one line per profile row (inspect/profile.hpp), units in the column names
///   (station_m, coverage, widest_gap_deg, height_mm, …); a field that is NaN is empty;
/// - `observations.json`: {"format": "sewer3d-observations", "version": 1, "observations":
///   [every field of each Observation, quantities as {name, value, unit}]};
/// - `observations.csv`: one line per observation for spreadsheets (write only);
/// - `observations.xml`: the observations in the structure of the ISYBAU Austauschformat
///   Abwasser (XML), Zustandsdaten of one pipe (write only; docs/inspection.md says which
///   elements and where their names come from).
///
/// Every file is written atomically; readers validate and throw FileError "PATH: field: …".

#include <filesystem>
#include <string>
#include <vector>

#include "sewer3d/inspect/observation.hpp"
#include "sewer3d/inspect/profile.hpp"

namespace sewer3d {

/// WS/inspection/ and its files.
struct InspectionFiles {
  std::filesystem::path folder, profile_csv, observations_json, observations_csv, observations_xml;
};
InspectionFiles InspectionFilesIn(const std::filesystem::path& workspace);

void WriteProfileCsv(const std::filesystem::path& path, const Profile& profile);
/// FileError when the header differs, a field is not a number (or empty where it must not
/// be: station_m, coverage, widest_gap_deg, nominal_diameter_mm), coverage is outside 0..1 or
/// the stations do not increase.
Profile ReadProfileCsv(const std::filesystem::path& path);

void WriteObservationsJson(const std::filesystem::path& path,
                           const std::vector<Observation>& observations);
/// FileError naming the field ("observations[2].clock_h") when the format or version is not
/// this one, a field is missing, unknown or of the wrong type, or a value is out of range
/// (clocks 0..12, confidence 0..1, lengths and crop sizes ≥ 0).
std::vector<Observation> ReadObservationsJson(const std::filesystem::path& path);

/// Columns: id, code, characterisation, station_m (2 decimals), length_m, clock_h,
/// clock_from_h, clock_to_h, at_joint (0/1), confidence, q1_name, q1_value, q1_unit, q2_name,
/// q2_value, q2_unit, remark. Text with a comma or quote is quoted (RFC 4180).
void WriteObservationsCsv(const std::filesystem::path& path,
                          const std::vector<Observation>& observations);

/// What the ISYBAU file says about the inspection besides the observations.
struct IsybauHeader {
  std::string object_name = "sewer3d";  ///< Objektbezeichnung of the inspected pipe
  std::string inspection_date;          ///< Inspektionsdatum, YYYY-MM-DD; empty: left out
  std::string creation_date;            ///< Erstellungsdatum, YYYY-MM-DD; empty: left out
  double profile_height_mm = 0.0;       ///< Profilhoehe (nominal); 0: left out
  double profile_width_mm = 0.0;        ///< Profilbreite (nominal); 0: left out
};

/// One RZustand per point observation; a continuous one (length_mm > 0) as a start (A) and an
/// end (B) entry with a running number, as EN 13508-2 records continuous defects.
void WriteObservationsIsybau(const std::filesystem::path& path,
                             const std::vector<Observation>& observations,
                             const IsybauHeader& header);

}  // namespace sewer3d
