#include "sewer3d/pipeline/register_outputs.hpp"

#include <fmt/core.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/g2o_io.hpp"
#include "sewer3d/io/registration_io.hpp"
#include "sewer3d/pipeline/register_stage.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;

int VertexOf(const AcquisitionNode& n) { return RegistrationVertexId(n.module, n.counter); }

/// The optimised graph with the acquisitions' vertex ids (accepted edges, in edges.csv order).
PoseGraph ExportGraph(const std::vector<AcquisitionNode>& nodes, const FusionResult& fused) {
  PoseGraph graph;
  for (size_t i = 0; i < nodes.size(); ++i)
    graph.SetNode(VertexOf(nodes[i]), fused.world_from_camera[i]);
  for (PoseEdge e : fused.graph.edges()) {
    e.from = VertexOf(nodes[e.from]);
    e.to = VertexOf(nodes[e.to]);
    graph.AddEdge(e);
  }
  graph.fixed_nodes() = {VertexOf(nodes.front())};
  return graph;
}

json SolveJson(const PoseGraphReport& r) {
  json j = {{"usable", r.usable},         {"initial_cost", r.initial_cost},
            {"final_cost", r.final_cost}, {"iterations", r.iterations},
            {"seconds", r.solve_seconds}, {"termination", r.termination}};
  if (!r.certificate_reason.empty() || r.certificate_applicable) {
    j["certificate"] = {{"applicable", r.certificate_applicable},
                        {"reason", r.certificate_reason},
                        {"lower_bound", r.lower_bound},
                        {"relative_gap", r.RelativeGap()},
                        {"relaxation_solved", r.relaxation_solved},
                        {"rank", r.relaxation_rank}};
  }
  return j;
}

json GravityJson(const GravityReport& g) {
  if (g.observations == 0) return {{"observations", 0}};
  const Eigen::Vector3d& d = g.down_in_model;
  return {{"observations", g.observations},
          {"rms_deg", g.rms_deg},
          {"max_deg", g.max_deg},
          {"down_in_model", {d.x(), d.y(), d.z()}},
          {"pipe_gradient_percent", 100.0 * d.z() / std::hypot(d.x(), d.y())}};
}

json CentrelineJson(const std::optional<CentrelineReport>& c) {
  if (!c) return {{"observations", 0}};
  const bool straight = !std::isfinite(c->bend_radius_mm);
  return {{"observations", c->observations},
          {"points", c->points},
          {"featureless_points", c->featureless_points},
          {"length_mm", c->length_mm},
          {"across_rms_mm", c->across_rms_mm},
          {"across_max_mm", c->across_max_mm},
          {"bend_radius_m", straight ? json(nullptr) : json(c->bend_radius_mm / 1000.0)},
          {"max_sagitta_mm", c->max_sagitta_mm}};
}

// The fused centreline's control points: station (the odometry's distance) and model frame.
std::string CentrelineCsv(const AxisCurve& curve) {
  std::string text = "station_mm,x_mm,y_mm,z_mm\n";
  for (size_t k = 0; k < curve.points.size(); ++k) {
    const Eigen::Vector3d& p = curve.points[k];
    text += fmt::format("{:.3f},{:.4f},{:.4f},{:.4f}\n",
                        curve.start_station_mm + static_cast<double>(k) * curve.spacing_mm, p.x(),
                        p.y(), p.z());
  }
  return text;
}

}  // namespace

std::string RegisterOptionsJson(const RegisterStageOptions& o) {
  const FeatureRegistrationOptions& f = o.pairs.features;
  const ProjectionRegistrationOptions& p = o.pairs.projection;
  const PriorEdgeOptions& r = o.priors;
  const json j = {
      {"neighbours",
       {{"nominal_diameter_mm", o.neighbours.nominal_diameter_mm},
        {"grid_step_px", o.neighbours.grid_step_px},
        {"min_overlap", o.neighbours.min_overlap},
        {"max_counter_gap", o.neighbours.max_counter_gap}}},
      {"features",
       {{"contrast_threshold", f.contrast_threshold},
        {"ratio", f.ratio},
        {"max_keypoints", f.max_keypoints},
        {"min_inliers", f.points.min_inliers}}},
      {"feature_registration", o.pairs.feature_registration},
      {"between_modules_floor",
       {o.pairs.between_modules_floor_mm, o.pairs.between_modules_floor_deg}},
      {"projection",
       {{"enabled", o.pairs.projection_fallback},
        {"sample_step_px", p.sample_step_px},
        {"photometric", p.photometric.enabled},
        {"max_distance_mm", p.max_distance_mm}}},
      {"priors",
       {{"rig", r.rig},
        {"odometry", r.odometry},
        {"straightness", r.straightness},
        {"rig_sigma_mm", r.rig_sigma_mm},
        {"rig_sigma_deg", r.rig_sigma_deg},
        {"odometry_noise_mm", r.odometry_noise_mm},
        {"min_bend_radius_mm", r.min_bend_radius_mm}}},
      {"fusion",
       {{"huber_delta", o.fusion.huber_delta},
        {"gate_chi2", o.fusion.gate_chi2},
        {"group_biases", o.fusion.group_biases},
        {"gravity", o.fusion.gravity},
        {"odometry_scale", o.fusion.odometry_scale},
        {"gravity_sigma_deg", o.fusion.gravity_sigma_deg},
        {"centreline",
         {{"enabled", o.fusion.centreline.enabled},
          {"spacing_mm", o.fusion.centreline.spacing_mm},
          {"bend_radius_mm", o.fusion.centreline.bend_radius_mm},
          {"featureless_bend_radius_mm", o.fusion.centreline.featureless_bend_radius_mm},
          {"axis_sigma_mm", o.fusion.centreline.axis_sigma_mm},
          {"axis_max_rms_mm", o.axis_max_rms_mm},
          {"axis_min_inliers", o.axis_min_inliers}}}}},
      {"min_depth_points", o.min_depth_points}};
  return j.dump();
}

std::string RegisterStageReportToJson(const RegisterStageReport& report) {
  json left_out = json::array();
  for (const LeftOutAcquisition& l : report.left_out)
    left_out.push_back({{"module", l.module}, {"counter", l.counter}, {"reason", l.reason}});
  json by_type = json::object();
  for (int t = 0; t < kRegistrationEdgeTypes; ++t) {
    const EdgeTypeStatistics& s = report.fusion.by_type[t];
    by_type[RegistrationEdgeTypeName(static_cast<RegistrationEdgeType>(t))] = {
        {"edges", s.edges},
        {"accepted", s.accepted},
        {"median_chi2", s.median_chi2},
        {"mean_chi2", s.mean_chi2},
        {"max_chi2", s.max_chi2},
        {"rms_translation_mm", s.rms_translation_mm},
        {"rms_rotation_deg", s.rms_rotation_deg}};
  }
  json module_pairs = json::array();
  for (const ModulePairAgreement& p : report.module_pairs) {
    module_pairs.push_back({{"modules", {p.module_a, p.module_b}},
                            {"edges", p.edges},
                            {"rejected", p.rejected},
                            {"median_rejected_offset_mm", p.median_rejected_offset_mm}});
  }
  json biases = json::array();
  for (const EdgeGroupBias& b : report.fusion.biases) {
    const Eigen::Vector3d turn = b.bias.tail<3>() * (180.0 / M_PI);
    biases.push_back({{"type", RegistrationEdgeTypeName(b.type)},
                      {"modules", {b.module_a, b.module_b}},
                      {"counter_step", b.counter_step},
                      {"edges", b.edges},
                      {"translation_mm", {b.bias[0], b.bias[1], b.bias[2]}},
                      {"rotation_deg", {turn.x(), turn.y(), turn.z()}}});
  }
  const CarrierOffsetEstimate& c = report.carrier_offset;
  const json j = {
      {"stage", "register"},
      {"acquisitions", report.acquisitions},
      {"nodes", report.nodes},
      {"left_out", left_out},
      {"initial_poses",
       {{"without_pattern", report.initial.without_pattern},
        {"outside_odometry", report.initial.outside_odometry},
        {"odometry_backwards", report.initial.odometry_backwards},
        {"odometry_dropped", report.initial.odometry_dropped},
        {"in_odometry_gap", report.initial.in_odometry_gap},
        {"odometry_warnings", report.odometry_warnings}}},
      {"carrier_offset",
       {{"valid", c.valid},
        {"axis_in_carrier_mm", {c.axis_in_carrier_mm.x(), c.axis_in_carrier_mm.y()}},
        {"diameter_mm", c.diameter_mm},
        {"rms_mm", c.rms_mm},
        {"inlier_fraction", c.inlier_fraction},
        {"modules", c.modules},
        {"nodes_with_axis", report.nodes_with_axis}}},
      {"neighbours",
       {{"candidates", report.neighbours.candidates}, {"kept", report.neighbours.kept}}},
      {"pairs",
       {{"total", report.pairs},
        {"done", report.pairs_done},
        {"skipped", report.pairs_skipped},
        {"failed", report.pairs_failed},
        {"feature", report.feature_edges},
        {"projection", report.projection_edges},
        {"textured", report.textured_edges},
        {"degenerate", report.degenerate_edges}}},
      {"prior_edges", report.prior_edges},
      {"fusion",
       {{"usable", report.fusion.usable},
        {"rejected", report.fusion.rejected},
        {"gate_rounds", report.fusion.gate_rounds},
        {"first_solve", SolveJson(report.fusion.first_solve)},
        {"final_solve", SolveJson(report.fusion.final_solve)},
        {"by_type", by_type},
        {"module_pairs", module_pairs},
        {"group_biases", biases},
        {"gravity", GravityJson(report.fusion.gravity)},
        {"centreline", CentrelineJson(report.fusion.centreline)},
        {"rig_warnings", report.rig_warnings},
        {"graph_warnings", report.graph_warnings}}},
      {"seconds",
       {{"stage", report.seconds},
        {"per_pair", report.seconds_per_pair},
        {"per_node", report.seconds_per_node}}},
      {"threads", report.threads}};
  return j.dump(2) + "\n";
}

void WriteRegistrationOutputs(const std::filesystem::path& folder, const Rig& rig,
                              const std::vector<AcquisitionNode>& nodes,
                              const std::vector<RegistrationEdge>& edges, const FusionResult& fused,
                              double length_scale_mm, const std::string& report_json) {
  std::vector<RegistrationPoseRow> poses;
  std::vector<GraphPictureNode> picture_nodes;
  for (size_t i = 0; i < nodes.size(); ++i) {
    poses.push_back(
        {nodes[i].module, nodes[i].counter, nodes[i].time_s, fused.world_from_camera[i]});
    picture_nodes.push_back(
        {fused.world_from_camera[i].translation.z(), rig.modules[nodes[i].module].clock_h});
  }
  std::vector<RegistrationEdgeRow> rows;
  std::vector<GraphPictureEdge> picture_edges;
  for (size_t k = 0; k < edges.size(); ++k) {
    const RegistrationEdge& e = edges[k];
    RegistrationEdgeRow row;
    row.from_module = nodes[e.a].module;
    row.from_counter = nodes[e.a].counter;
    row.to_module = nodes[e.b].module;
    row.to_counter = nodes[e.b].counter;
    row.type = RegistrationEdgeTypeName(e.type);
    row.inliers = e.inliers;
    row.rms_mm = e.rms_mm;
    row.eigenvalues = AnalyseInformation(e.information, length_scale_mm, 0.0).eigenvalues;
    row.chi2 = fused.chi2[k];
    row.accepted = fused.accepted[k];
    rows.push_back(row);
    picture_edges.push_back({e.a, e.b, static_cast<int>(e.type), fused.accepted[k]});
  }
  WriteRegistrationPoses(folder / "poses.csv", poses);
  WriteRegistrationEdges(folder / "edges.csv", rows);
  WriteFileAtomically(folder / "graph.g2o", [&](const std::filesystem::path& temporary) {
    WriteG2o(temporary, ExportGraph(nodes, fused));
  });
  WriteRegistrationGraphPicture(folder / "graph.png", picture_nodes, picture_edges);
  if (fused.centreline)
    WriteTextFileAtomically(folder / "centreline.csv", CentrelineCsv(*fused.centreline));
  WriteTextFileAtomically(folder / "report.json", report_json);
}

}  // namespace sewer3d
