#pragma once
/// \file
/// How good the registration stage's poses are on a simulated run (issue 15 acceptance;
/// docs/registration.md), against truth/poses.csv (true world_from_carrier of every image;
/// the true camera = world_from_carrier · carrier_from_camera of rig.json):
/// - absolute trajectory error of the camera centres after one rigid alignment of the model
///   frame onto the truth's world (Umeyama, no scale), overall and per material of the pipe
///   section each camera sits in (truth/scenario.json);
/// - relative pose error of the accepted edges (graph.g2o with edges.csv) against the true
///   relative poses: median translation (mm) and rotation (deg) per edge type;
/// - NEES of the accepted edges, rᵀΩr of the measurement at the true poses (χ²(6): mean 6).

#include <filesystem>
#include <map>
#include <string>

#include "sewer3d/core/rigid3.hpp"

namespace sewer3d {

struct AteFigures {
  int nodes = 0;
  double rms_mm = 0.0;
  double max_mm = 0.0;
};

struct EdgeErrorFigures {
  int accepted = 0;
  double median_translation_mm = 0.0;
  double median_rotation_deg = 0.0;
  double mean_nees = 0.0;
  double median_nees = 0.0;
};

struct RegistrationEvaluation {
  AteFigures ate;
  std::map<std::string, AteFigures> ate_by_material;  ///< by material name
  std::map<std::string, EdgeErrorFigures> edges;      ///< by edge type
  Rigid3d truth_from_model;                           ///< the alignment
};

/// Reads the run (rig, truth/) and WS/registration/{poses.csv, edges.csv, graph.g2o}; FileError
/// when a file is missing or malformed, or a pose has no truth.
RegistrationEvaluation EvaluateRegistration(const std::filesystem::path& run_folder,
                                            const std::filesystem::path& workspace);

/// The figures as JSON text.
std::string RegistrationEvaluationToJson(const RegistrationEvaluation& evaluation);

}  // namespace sewer3d
