#pragma once
/// \file
/// How good the inspection's observations are on a simulated run (issue 18 acceptance;
/// docs/inspection.md "Accuracy"). Every true joint, deformed section and wall feature of the
/// pipe world is put into the model's (station, clock) through the truth alignment
/// (truth_alignment.hpp) and the model's centreline, and matched with the observation of its
/// code nearest to it; what it says is compared with the true dimensions. True items outside
/// the stations the inspection searched are "not inspected"; observations that match no true
/// item are "invented".

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/inspect/observation.hpp"
#include "sewer3d/model/pipe_map.hpp"
#include "sewer3d/sim/pipe_world.hpp"
#include "sewer3d/simeval/profile_evaluation.hpp"

namespace sewer3d {

/// One true item and what the inspection said of it.
struct TrueItemMatch {
  std::string truth_id;        ///< J1, D2, C1, …
  std::string code;            ///< its EN 13508-2 code
  double station_mm = 0.0;     ///< true, in model stations
  double clock_h = 12.0;       ///< true, in the model's clock
  bool inspected = false;      ///< inside the stations the inspection searched
  std::string observation_id;  ///< empty: not found
  double station_error_mm = 0.0;
  double clock_error_h = 0.0;
  /// Per quantity: name, true value, measured value (measured − true is the error).
  struct Value {
    std::string name;
    double truth = 0.0;
    double measured = 0.0;
  };
  std::vector<Value> values;
};

struct InspectionEvaluation {
  std::vector<TrueItemMatch> items;
  std::vector<std::string> invented;  ///< ids of observations matching no true item
  int inspected = 0, found = 0;
};

struct InspectionEvaluationOptions {
  double match_station_mm = 40.0;  ///< an observation this close (and clock_h) can match
  double match_clock_h = 1.5;
  double inspected_from_mm = -1e300;  ///< model stations the inspection searched
  double inspected_to_mm = 1e300;
  /// When set: each true item, placed in the model by truth_from_model, is placed again by the
  /// transform this gives at that model station (a local alignment, LocalTruthFromModel).
  std::function<Rigid3d(double model_station_mm)> truth_from_model_near;
};

/// Matches `observations` with the true items of `truth` (model frame put onto the world by
/// truth_from_model; the model's `centreline`).
InspectionEvaluation EvaluateObservations(const std::vector<Observation>& observations,
                                          const PipeGeometry& truth,
                                          const Rigid3d& truth_from_model,
                                          const Centreline& centreline,
                                          const InspectionEvaluationOptions& options);

/// Both halves of `sewer3d evaluate inspection`.
struct InspectionFilesEvaluation {
  InspectionEvaluation observations;
  ProfileEvaluation profile;
};

/// Reads the run (rig, truth/), WS/registration/poses.csv, WS/model/model.json and
/// WS/inspection/ (observations.json, profile.csv, report.json for the stations searched) and
/// evaluates them; FileError when a file is missing or malformed. `local_alignment_mm` > 0:
/// every observation is judged against the truth aligned by the cameras within ± that many mm
/// of it (InspectionEvaluationOptions::truth_from_model_near); 0: one alignment for the run.
InspectionFilesEvaluation EvaluateInspection(const std::filesystem::path& run_folder,
                                             const std::filesystem::path& workspace,
                                             double local_alignment_mm = 0.0);

/// The matches, the invented observations and the profile's figures as JSON text.
std::string InspectionEvaluationToJson(const InspectionFilesEvaluation& evaluation);

}  // namespace sewer3d
