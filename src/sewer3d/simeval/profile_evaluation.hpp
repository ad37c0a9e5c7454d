#pragma once
/// \file
/// How good the inspection's cross-section profile (inspect/profile.hpp) is on a simulated run
/// (issue 18 acceptance: inner circumference within 0.08 % and ovality within 0.2 % absolute
/// of the truth per station on clean stretches; docs/inspection.md "Profile accuracy").
///
/// Each profile row is set against the *true ring at the same place*: from the model's axis
/// point at the row's station, rays in the row's clock directions in the model's cross-section
/// plane, mapped onto the truth's world by the registration's alignment (truth_alignment.hpp),
/// meet the true wall (PipeGeometry::Intersect, i.e. WallRadiusMm: deformation, joints and
/// features included); the true ring's radii are measured by the same MeasureRing as the
/// model's. A row is *clean* when the pipe world's station of its axis point lies more than
/// `clean_margin_mm` from every joint and from every feature's extent (the joints and features
/// of truth/scenario.json's pipe world, which truth/features.json lists).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/inspect/profile.hpp"
#include "sewer3d/model/pipe_map.hpp"
#include "sewer3d/sim/pipe_world.hpp"

namespace sewer3d {

struct ProfileEvaluationOptions {
  double clean_margin_mm = 50.0;  ///< distance from joints and features of clean stations
  int ring_directions = 720;      ///< rays per true ring
  void Check() const;
};

/// One profile row against the true ring. Errors are model − truth: circumference in % of the
/// truth, ovalities in percentage points, lengths in mm; NaN where the row is not measured or
/// the true wall was not found all around.
struct ProfileRowEvaluation {
  double station_mm = 0.0;       ///< model station
  double true_station_mm = 0.0;  ///< the pipe world's station of the row's axis point
  bool clean = false;
  ProfileRow model;
  ProfileRow truth;
  double circumference_error_pct = 0.0;
  double mean_diameter_error_mm = 0.0;
  double ovality_en_error_pct = 0.0;
  double ovality_astm_error_pct = 0.0;
  double height_error_mm = 0.0;
  double width_error_mm = 0.0;
};

/// |error| over the clean rows with an error.
struct AbsErrorSummary {
  int rows = 0;
  double median = 0.0;
  double p95 = 0.0;
  double max = 0.0;
};

struct ProfileEvaluation {
  std::vector<ProfileRowEvaluation> rows;
  int clean_rows = 0;  ///< clean, measured and with a true ring
  AbsErrorSummary circumference_pct, mean_diameter_mm, ovality_en_pct, ovality_astm_pct, height_mm,
      width_mm;
};

/// The true wall's distance from the model's axis point at `station_mm`, in `directions` clock
/// directions (k + ½) · 2π / directions of the model's cross-section there; nullopt when a ray
/// finds no wall.
std::optional<std::vector<double>> TrueRing(const PipeGeometry& truth, const Centreline& centreline,
                                            const Rigid3d& truth_from_model, double station_mm,
                                            int directions);

/// True when the pipe world's station `true_station_mm` is more than `margin_mm` from every
/// joint and every feature's extent along the pipe.
bool IsCleanStation(const PipeGeometry& truth, double true_station_mm, double margin_mm);

/// The numeric core: `profile` (computed with `profile_options` on maps over `centreline`)
/// against the true pipe, the model frame mapped by `truth_from_model`. Throws
/// std::invalid_argument on invalid options.
ProfileEvaluation EvaluateProfileAgainstTruth(const Profile& profile, const Centreline& centreline,
                                              const PipeGeometry& truth,
                                              const Rigid3d& truth_from_model,
                                              const ProfileOptions& profile_options,
                                              const ProfileEvaluationOptions& options);

/// The summaries and the per-row errors as JSON text.
std::string ProfileEvaluationToJson(const ProfileEvaluation& evaluation);

}  // namespace sewer3d
