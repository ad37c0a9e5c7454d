#include "sewer3d/simeval/registration_evaluation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/g2o_io.hpp"
#include "sewer3d/io/registration_io.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/report/profile_plots.hpp"
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

EdgeErrorFigures Figures(const std::vector<EdgeError>& list) {
  std::vector<double> dt, dr, wall, nees;
  for (const EdgeError& x : list) {
    dt.push_back(x.translation_mm);
    dr.push_back(x.rotation_deg);
    wall.push_back(x.wall_mm);
    nees.push_back(x.nees);
  }
  EdgeErrorFigures f;
  f.accepted = static_cast<int>(list.size());
  f.median_translation_mm = Median(dt);
  f.median_rotation_deg = Median(dr);
  f.median_wall_mm = Median(wall);
  for (double x : nees) f.mean_nees += x / static_cast<double>(nees.size());
  f.median_nees = Median(nees);
  return f;
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
    const Eigen::Vector3d offset =
        e.truth_from_model * poses[i].world_from_camera.translation - c_world;
    e.node_errors.push_back({poses[i].module, poses[i].counter, c_world, offset});
    const double error = offset.norm();
    Add(e.ate, error);
    const int section = pipe.Locate(c_world).section;
    Add(e.ate_by_material[MaterialName(pipe.world().sections[section].material)], error);
  }
  Finish(e.ate);
  for (auto& [name, f] : e.ate_by_material) Finish(f);

  // Accepted rows of edges.csv are graph.g2o's edges, in order.
  const std::vector<RegistrationEdgeRow> rows = ReadRegistrationEdges(folder / "edges.csv");
  const PoseGraph graph = ReadG2o(folder / "graph.g2o");
  const Eigen::Vector3d on_wall(0.0, 0.0, 150.0);  // in the second camera's frame
  size_t k = 0;
  for (const RegistrationEdgeRow& row : rows) {
    if (!row.accepted) continue;
    if (k >= graph.edges().size())
      throw FileError(folder / "graph.g2o", "fewer edges than accepted rows in edges.csv");
    const PoseEdge& edge = graph.edges()[k++];
    const Rigid3d& wa = truth.at(edge.from);
    const Rigid3d& wb = truth.at(edge.to);
    const Rigid3d true_ab = wa.Inverse() * wb;
    const Eigen::Matrix<double, 6, 1> r = EdgeResidual(edge, wa, wb);
    const EdgeError error{
        row.from_module,
        row.from_counter,
        row.to_module,
        row.to_counter,
        row.type,
        (edge.a_from_b.translation - true_ab.translation).norm(),
        edge.a_from_b.rotation.angularDistance(true_ab.rotation) * kRadToDeg,
        (edge.a_from_b * on_wall - true_ab * on_wall).norm(),
        r.dot(edge.information * r),
        (Eigen::Matrix<double, 6, 1>() << r.head<3>(), r.tail<3>() * kRadToDeg).finished()};
    e.edge_errors.push_back(error);
  }
  std::map<std::string, std::vector<EdgeError>> by_type, by_kind;
  for (const EdgeError& x : e.edge_errors) {
    by_type[x.type].push_back(x);
    if (x.type == "feature" || x.type == "projection")
      by_kind[x.type + (x.from_module == x.to_module ? "/along" : "/around")].push_back(x);
  }
  for (const auto& [key, list] : by_type) e.edges[key] = Figures(list);
  for (const auto& [key, list] : by_kind) e.edges_by_kind[key] = Figures(list);
  return e;
}

std::string RegistrationEvaluationToJson(const RegistrationEvaluation& e) {
  auto ate = [](const AteFigures& f) {
    return nlohmann::json{{"nodes", f.nodes}, {"rms_mm", f.rms_mm}, {"max_mm", f.max_mm}};
  };
  nlohmann::json materials = nlohmann::json::object(), edges = nlohmann::json::object();
  for (const auto& [name, f] : e.ate_by_material) materials[name] = ate(f);
  auto figures = [](const EdgeErrorFigures& f) {
    return nlohmann::json{{"accepted", f.accepted},
                          {"median_translation_mm", f.median_translation_mm},
                          {"median_rotation_deg", f.median_rotation_deg},
                          {"median_wall_mm", f.median_wall_mm},
                          {"mean_nees", f.mean_nees},
                          {"median_nees", f.median_nees}};
  };
  nlohmann::json by_kind = nlohmann::json::object();
  for (const auto& [type, f] : e.edges) edges[type] = figures(f);
  for (const auto& [key, f] : e.edges_by_kind) by_kind[key] = figures(f);
  const nlohmann::json j = {{"ate", ate(e.ate)},
                            {"ate_by_material", materials},
                            {"edges", edges},
                            {"edges_by_kind", by_kind}};
  return j.dump(2) + "\n";
}

std::string EdgeErrorsToCsv(const std::vector<EdgeError>& errors) {
  std::string text =
      "from_module,from_counter,to_module,to_counter,type,translation_mm,rotation_deg,wall_mm,"
      "nees,tx_mm,ty_mm,tz_mm,rx_deg,ry_deg,rz_deg\n";
  for (const EdgeError& x : errors) {
    text += fmt::format("{},{},{},{},{},{:.4f},{:.5f},{:.4f},{:.3f}", x.from_module, x.from_counter,
                        x.to_module, x.to_counter, x.type, x.translation_mm, x.rotation_deg,
                        x.wall_mm, x.nees);
    for (int i = 0; i < 6; ++i) text += fmt::format(",{:.5f}", x.residual[i]);
    text += "\n";
  }
  return text;
}

std::string NodeErrorsToCsv(const std::vector<NodeError>& errors) {
  std::string text = "module,counter,x_mm,y_mm,z_mm,ex_mm,ey_mm,ez_mm\n";
  for (const NodeError& n : errors) {
    text += fmt::format("{},{},{:.3f},{:.3f},{:.3f},{:.4f},{:.4f},{:.4f}\n", n.module, n.counter,
                        n.true_centre_mm.x(), n.true_centre_mm.y(), n.true_centre_mm.z(),
                        n.error_mm.x(), n.error_mm.y(), n.error_mm.z());
  }
  return text;
}

std::vector<CarrierError> CarrierErrors(const std::vector<NodeError>& errors) {
  std::map<int, std::pair<int, CarrierError>> sums;  // counter → cameras, sums
  for (const NodeError& n : errors) {
    auto& [count, sum] = sums[n.counter];
    ++count;
    sum.counter = n.counter;
    sum.true_centre_mm += n.true_centre_mm;
    sum.error_mm += n.error_mm;
  }
  std::vector<CarrierError> carrier;
  for (auto& [counter, entry] : sums) {
    CarrierError c = entry.second;
    c.true_centre_mm /= entry.first;
    c.error_mm /= entry.first;
    carrier.push_back(c);
  }
  return carrier;
}

std::string TrajectoryErrorSvg(const std::vector<NodeError>& errors) {
  std::vector<double> station;
  PlotSeries x{"x (across)", "#c0392b", {}}, y{"y (down)", "#1f5fbf", {}},
      z{"z (along)", "#2e8b57", {}};
  for (const CarrierError& c : CarrierErrors(errors)) {
    station.push_back(c.true_centre_mm.z() / 1000.0);
    x.y.push_back(c.error_mm.x());
    y.y.push_back(c.error_mm.y());
    z.y.push_back(c.error_mm.z());
  }
  return StandaloneSvg(LinePlotSvg(station, "true station of the cameras (m)", {x, y, z},
                                   "mean camera error per counter (mm)"));
}

}  // namespace sewer3d
