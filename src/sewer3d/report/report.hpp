#pragma once
/// \file
/// The inspection report (docs/report.md): WS/report/index.html, one self-contained offline page
/// — run summary, unrolled texture and displacement heat map (zoomable), the 3D viewer, profile
/// plots, the observation table with crops, and the accuracy figures of a simulated run. The
/// caller fills ReportInputs (GatherReportInputs in workspace_inputs.hpp reads a workspace);
/// what is missing is left out with a visible note.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sewer3d/inspect/observation.hpp"
#include "sewer3d/inspect/profile.hpp"

namespace sewer3d {

struct ReportOptions {
  int map_station_px = 4096;  ///< map pictures at most this long along the pipe
  int map_clock_px = 2048;    ///< … and this high around it
  int viewer_rows = 1024;     ///< the viewer's vertex rows along the pipe, at most
  int viewer_clocks = 256;    ///< … and around it
  int crop_px = 240;          ///< an observation's crop at most this long on its long side
  /// Crops for the first this many observations of the table (each costs up to ~1 MB while the
  /// maps are read and ~20 kB of page); the rest are listed without one, with a note.
  int max_crops = 500;
  int jpeg_quality = 88;  ///< of the texture pictures (0..100)
  void Check() const;
};

/// One stage of workspace.json: how long its last run took.
struct StageTime {
  std::string stage;
  double seconds = 0.0;
  bool done = false;
};

/// One WS/evaluation/<name>/evaluation.json, as text.
struct EvaluationText {
  std::string name;
  std::string json;
};

struct ReportInputs {
  std::string title = "sewer3d inspection report";
  std::filesystem::path model_dir;  ///< WS/model (model.json and the maps, whole or tiles)
  std::string run_folder;
  std::vector<std::pair<std::string, std::string>> run_facts;  ///< label, value (run.json)
  std::vector<StageTime> stages;
  std::optional<Profile> profile;                        ///< nullopt: not computed
  std::optional<std::vector<Observation>> observations;  ///< nullopt: not computed
  std::vector<EvaluationText> evaluations;
  std::vector<std::string> notes;  ///< the caller's notes, shown at the top
  ReportOptions options;
};

struct ReportSummary {
  std::uintmax_t html_bytes = 0;
  bool maps = false;    ///< the map pictures (and crops) are in the report
  bool viewer = false;  ///< the 3D viewer is in the report
  /// One line (FileError text) when the model or its maps could not be read; empty otherwise.
  std::string maps_problem;
  std::vector<std::string> notes;  ///< every note the page shows (what is missing and why)
};

/// Writes the report for `inputs` to `html` atomically (its folder created). A missing or
/// unreadable model is no error: the page says so (summary.maps_problem). FileError when the
/// page cannot be written; std::invalid_argument for bad options.
ReportSummary WriteReport(const ReportInputs& inputs, const std::filesystem::path& html);

}  // namespace sewer3d
