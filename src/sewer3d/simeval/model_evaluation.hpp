#pragma once
/// \file
/// How good the model stage's pipe model is on a simulated run (issue 16 item 5; docs/model.md
/// "Accuracy against the simulator"). The model frame is put onto the truth's world by the
/// registration's alignment (truth_alignment.hpp: Umeyama of the registered camera centres onto
/// the true ones), then every evaluated cell's map point (model/pipe_map.hpp: centreline(station)
/// + (radius + displacement) · direction(clock)) is compared with the true wall:
/// - the signed error = ρ − true wall radius at the point (PipeGeometry; positive: the model lies
///   outside the true wall), overall, per coverage class, per material of the true pipe section
///   and per clock hour (the modules' seams show as hours with larger errors);
/// - per station bin, the circumference of the model's cross-section (in the centreline's normal
///   plane) against the true wall's cut by the same plane (rays from the same axis point in the
///   same clock directions), for cross-sections the model covers all around; both averaged
///   over each direction's sector and a band of stations, as a profile ring is;
/// - per evaluated map row, the lateral offset of the model's axis from the true one (the first
///   harmonic of the row's errors around the clock: registration drift and centreline error),
///   and the errors with it removed (the surface's own error: noise, seams, radius).

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/io/model_io.hpp"
#include "sewer3d/sim/pipe_world.hpp"

namespace sewer3d {

struct ModelEvaluationOptions {
  /// Every stride-th row and column of the map is evaluated; 0: automatic, the smallest
  /// stride that checks at most target_cells covered cells.
  int stride = 0;
  std::int64_t target_cells = 3'000'000;
  /// A given stride may evaluate at most this many covered cells: each costs ~32 bytes of
  /// error buffers (1 GB here), on top of the model's maps.
  std::int64_t max_cells = 30'000'000;
  double station_bin_mm = 10.0;        ///< circumference: one cross-section per bin
  int circumference_directions = 360;  ///< clock directions (1° sectors) per cross-section
  /// Each sector's wall is averaged over ± this of station (a profile ring's band; 0: one row).
  double circumference_half_band_mm = 1.0;
  /// Axis offset per row: cells with |error| above this (joint gaps) are left out of the fit.
  double axis_outlier_mm = 2.0;
  /// "Away from step faces" (issue 16): cells whose true station lies more than this from every
  /// joint's gap and every feature's extent (IsCleanStation) form the `clean` class.
  double clean_margin_mm = 10.0;
  void Check() const;
};

/// Signed errors (mm) of a set of cells.
struct ErrorFigures {
  std::int64_t cells = 0;
  double mean_mm = 0.0;  ///< bias
  double rms_mm = 0.0;
  double median_abs_mm = 0.0;
  double p95_abs_mm = 0.0;
  double max_abs_mm = 0.0;
};

/// One cross-section: the model's circumference against the true wall's in the same plane.
struct CircumferenceSample {
  double station_mm = 0.0;  ///< model station
  double model_mm = 0.0;
  double truth_mm = 0.0;
};

struct CircumferenceFigures {
  int sections = 0;  ///< cross-sections compared (fully covered, true wall found all around)
  double mean_diff_mm = 0.0;  ///< model − truth
  double mean_abs_diff_mm = 0.0;
  double max_abs_diff_mm = 0.0;
};

struct ModelEvaluation {
  int stride = 1;  ///< as used
  ErrorFigures all;
  std::map<std::string, ErrorFigures> by_coverage;  ///< "measured", "filled"
  std::map<std::string, ErrorFigures> by_material;  ///< MaterialName of the true section
  std::vector<ErrorFigures> by_clock_hour;  ///< 12: [0] 12–1 o'clock, [2] 2–3 o'clock, …
  /// |lateral axis offset| per row (cells = rows fitted; mean_mm = mean |offset|, median_abs_mm,
  /// p95_abs_mm, max_abs_mm of |offset|).
  ErrorFigures axis_offset;
  ErrorFigures after_axis_offset;        ///< the fitted rows' errors with their axis offset removed
  ErrorFigures clean;                    ///< cells away from joints and features
  ErrorFigures clean_after_axis_offset;  ///< the same with their row's axis offset removed
  std::map<std::string, ErrorFigures> after_axis_offset_by_material;
  CircumferenceFigures circumference;
  std::vector<CircumferenceSample> circumference_profile;
  Rigid3d truth_from_model;
  MapGrid grid;  ///< the model's
  /// The evaluated cells' signed errors: row i = map row stride/2 + i · stride, column j = map
  /// column stride/2 + j · stride; NaN where the map has no data.
  cv::Mat1f error_mm;
  cv::Mat1f after_axis_offset_mm;  ///< the same with each row's axis offset removed (NaN: none)
};

/// Evaluates `model` against the true pipe, the model frame mapped by `truth_from_model`.
/// Throws std::invalid_argument on invalid options.
ModelEvaluation EvaluatePipeModel(const PipeModel& model, const PipeGeometry& truth,
                                  const Rigid3d& truth_from_model,
                                  const ModelEvaluationOptions& options);

/// Reads the run (rig, truth/), WS/registration/poses.csv and WS/model/ and evaluates; FileError
/// when a file is missing or malformed.
ModelEvaluation EvaluateModel(const std::filesystem::path& run_folder,
                              const std::filesystem::path& workspace,
                              const ModelEvaluationOptions& options);

/// The figures (no error map) as JSON text.
std::string ModelEvaluationToJson(const ModelEvaluation& evaluation);

/// error_map.png for people: the unrolled pipe (station along x, clock down y, crown at the
/// top) coloured by the signed error (inward blue, 0 white, outward red, saturating at
/// ±range_mm; no data black), at most `length_px` along the pipe, with station and clock tick
/// labels and a colour bar; `after_axis_offset`: the errors with each row's axis offset removed.
/// BGR.
cv::Mat3b ModelErrorMap(const ModelEvaluation& evaluation, double range_mm = 1.0,
                        int length_px = 2000, bool after_axis_offset = false);

}  // namespace sewer3d
