#pragma once
/// \file
/// How good the registration stage's poses are on a simulated run (issue 15 acceptance;
/// docs/registration.md), against truth/poses.csv (true world_from_carrier of every image;
/// the true camera = world_from_carrier · carrier_from_camera of rig.json):
/// - absolute trajectory error of the camera centres after one rigid alignment of the model
///   frame onto the truth's world (Umeyama, no scale), overall and per material of the pipe
///   section each camera sits in (truth/scenario.json);
/// - relative pose error of the accepted edges (graph.g2o with edges.csv) against the true
///   relative poses: median translation (mm) and rotation (deg) per edge type, and the
///   distance by which the edge misplaces the wall point 150 mm along the second camera's axis
///   (where the two views meet the wall: a rotation error about that point moves the camera
///   centre far more than the wall);
/// - NEES of the accepted edges, rᵀΩr of the measurement at the true poses (χ²(6): mean 6);
///   the pairwise edges also split into pairs of one module and of two.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

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
  double median_wall_mm = 0.0;
  double mean_nees = 0.0;
  double median_nees = 0.0;
};

/// One accepted edge against the truth (rows of evaluation/registration/edges.csv).
struct EdgeError {
  int from_module = 0, from_counter = 0, to_module = 0, to_counter = 0;
  std::string type;
  double translation_mm = 0.0, rotation_deg = 0.0, wall_mm = 0.0, nees = 0.0;
  /// The edge's residual at the true poses (EdgeResidual): translation in mm in the first
  /// camera's frame, rotation vector in degrees; signed, so that a bias shared by the edges of
  /// one pair of modules shows.
  Eigen::Matrix<double, 6, 1> residual = Eigen::Matrix<double, 6, 1>::Zero();
};

/// One camera centre against the truth (rows of evaluation/registration/nodes.csv).
struct NodeError {
  int module = 0, counter = 0;
  Eigen::Vector3d true_centre_mm = Eigen::Vector3d::Zero();  ///< world
  Eigen::Vector3d error_mm = Eigen::Vector3d::Zero();        ///< aligned model − truth, world
};

struct RegistrationEvaluation {
  AteFigures ate;
  std::vector<NodeError> node_errors;                 ///< in poses.csv's order
  std::vector<EdgeError> edge_errors;                 ///< accepted edges, in edges.csv's order
  std::map<std::string, AteFigures> ate_by_material;  ///< by material name
  std::map<std::string, EdgeErrorFigures> edges;      ///< by edge type
  /// Pairwise edges by type and kind: "feature/along" (both acquisitions of one module),
  /// "feature/around" (two modules), the same for "projection".
  std::map<std::string, EdgeErrorFigures> edges_by_kind;
  Rigid3d truth_from_model;  ///< the alignment
};

/// Reads the run (rig, truth/) and WS/registration/{poses.csv, edges.csv, graph.g2o}; FileError
/// when a file is missing or malformed, or a pose has no truth.
RegistrationEvaluation EvaluateRegistration(const std::filesystem::path& run_folder,
                                            const std::filesystem::path& workspace);

/// The figures as JSON text.
std::string RegistrationEvaluationToJson(const RegistrationEvaluation& evaluation);
/// Every accepted edge's errors as CSV text (from_module,from_counter,to_module,to_counter,type,
/// translation_mm,rotation_deg,wall_mm,nees, then the residual as tx_mm,ty_mm,tz_mm,rx_deg,ry_deg,
/// rz_deg).
std::string EdgeErrorsToCsv(const std::vector<EdgeError>& errors);
/// Per counter (ascending), the mean of its cameras' true centres and of their errors: the
/// carrier's error along the run.
struct CarrierError {
  int counter = 0;
  Eigen::Vector3d true_centre_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d error_mm = Eigen::Vector3d::Zero();
};
std::vector<CarrierError> CarrierErrors(const std::vector<NodeError>& errors);

/// CarrierErrors as an SVG file: world x, y (down) and z (along the pipe) over the true station
/// (m).
std::string TrajectoryErrorSvg(const std::vector<NodeError>& errors);
/// Every camera centre's error as CSV text (module,counter,x_mm,y_mm,z_mm of the true centre,
/// ex_mm,ey_mm,ez_mm: the aligned registered centre − the true one, world axes).
std::string NodeErrorsToCsv(const std::vector<NodeError>& errors);

}  // namespace sewer3d
