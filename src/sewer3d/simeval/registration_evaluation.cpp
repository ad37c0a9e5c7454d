#include "sewer3d/simeval/registration_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/g2o_io.hpp"
#include "sewer3d/io/registration_io.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/simeval/truth_alignment.hpp"
#include "sewer3d/simio/render_json.hpp"
#include "sewer3d/simio/scenario_io.hpp"

namespace sewer3d {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

void Add(AteFigures& f, double error) {
  ++f.nodes;
  f.rms_mm += error * error;
  f.max_mm = std::max(f.max_mm, error);
}

void Finish(AteFigures& f) {
  if (f.nodes > 0) f.rms_mm = std::sqrt(f.rms_mm / f.nodes);
}

}  // namespace

RegistrationEvaluation EvaluateRegistration(const std::filesystem::path& run_folder,
                                            const std::filesystem::path& workspace) {
  const CaptureRun run = LoadRun(run_folder);
  const TruthAlignment alignment = AlignRegistrationToTruth(run, run_folder, workspace);
  const std::map<int, Rigid3d>& truth = alignment.truth;
  const std::vector<RegistrationPoseRow>& poses = alignment.poses;
  const PipeGeometry pipe(ReadScenario(run_folder / "truth" / "scenario.json").world);
  const std::filesystem::path folder = workspace / "registration";
  RegistrationEvaluation e;
  e.truth_from_model = alignment.truth_from_model;
  for (size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Vector3d c_world = alignment.true_centres.col(static_cast<Eigen::Index>(i));
    const double error =
        (e.truth_from_model * poses[i].world_from_camera.translation - c_world).norm();
    Add(e.ate, error);
    const int section = pipe.Locate(c_world).section;
    Add(e.ate_by_material[MaterialName(pipe.world().sections[section].material)], error);
  }
  Finish(e.ate);
  for (auto& [name, f] : e.ate_by_material) Finish(f);

  // Accepted rows of edges.csv are graph.g2o's edges, in order.
  const std::vector<RegistrationEdgeRow> rows = ReadRegistrationEdges(folder / "edges.csv");
  const PoseGraph graph = ReadG2o(folder / "graph.g2o");
  std::map<std::string, std::vector<double>> dt, dr, nees;
  size_t k = 0;
  for (const RegistrationEdgeRow& row : rows) {
    if (!row.accepted) continue;
    if (k >= graph.edges().size())
      throw FileError(folder / "graph.g2o", "fewer edges than accepted rows in edges.csv");
    const PoseEdge& edge = graph.edges()[k++];
    const Rigid3d& wa = truth.at(edge.from);
    const Rigid3d& wb = truth.at(edge.to);
    const Rigid3d true_ab = wa.Inverse() * wb;
    dt[row.type].push_back((edge.a_from_b.translation - true_ab.translation).norm());
    dr[row.type].push_back(edge.a_from_b.rotation.angularDistance(true_ab.rotation) * kRadToDeg);
    const Eigen::Matrix<double, 6, 1> r = EdgeResidual(edge, wa, wb);
    nees[row.type].push_back(r.dot(edge.information * r));
  }
  for (auto& [type, list] : nees) {
    EdgeErrorFigures& f = e.edges[type];
    f.accepted = static_cast<int>(list.size());
    f.median_translation_mm = Median(dt[type]);
    f.median_rotation_deg = Median(dr[type]);
    for (double x : list) f.mean_nees += x / static_cast<double>(list.size());
    f.median_nees = Median(list);
  }
  return e;
}

std::string RegistrationEvaluationToJson(const RegistrationEvaluation& e) {
  auto ate = [](const AteFigures& f) {
    return nlohmann::json{{"nodes", f.nodes}, {"rms_mm", f.rms_mm}, {"max_mm", f.max_mm}};
  };
  nlohmann::json materials = nlohmann::json::object(), edges = nlohmann::json::object();
  for (const auto& [name, f] : e.ate_by_material) materials[name] = ate(f);
  for (const auto& [type, f] : e.edges) {
    edges[type] = {{"accepted", f.accepted},
                   {"median_translation_mm", f.median_translation_mm},
                   {"median_rotation_deg", f.median_rotation_deg},
                   {"mean_nees", f.mean_nees},
                   {"median_nees", f.median_nees}};
  }
  const nlohmann::json j = {{"ate", ate(e.ate)}, {"ate_by_material", materials}, {"edges", edges}};
  return j.dump(2) + "\n";
}

}  // namespace sewer3d
