#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "sewer3d/pipeline/process_chain.hpp"

namespace sewer3d {

StageOutcome RgbdOutcome(const RgbdStageReport& report, const std::filesystem::path& workspace) {
  StageOutcome o;
  o.output = workspace / "rgbd" / "report.json";
  o.summary = fmt::format(
      "rgbd: {} acquisitions: {} done, {} skipped (done before), {} failed; {} points; "
      "{:.2f} s per acquisition, {:.1f} s in all ({} threads); colour: {}",
      report.acquisitions, report.done, report.skipped, report.failed, report.points,
      report.seconds_per_acquisition, report.seconds, report.threads, report.color_source);
  // A bad acquisition is left out and named; the stage fails only when nothing is left.
  constexpr int kListed = 10;
  for (size_t i = 0; i < report.warnings.size() && i < kListed; ++i)
    o.details.push_back("warning: rgbd: " + report.warnings[i]);
  if (report.warnings.size() > kListed)
    o.details.push_back(fmt::format("warning: rgbd: {} more warnings (see {})",
                                    report.warnings.size() - kListed, o.output.string()));
  int listed = 0;
  for (const RgbdAcquisitionSummary& s : report.results) {
    const RgbdAcquisitionResult* f = s.Failure();
    if (f == nullptr || listed++ >= kListed) continue;
    o.details.push_back(fmt::format("warning: rgbd: m{} counter {} left out: {}: {}", s.module,
                                    s.counter, f->file, f->reason));
  }
  if (listed > kListed)
    o.details.push_back(fmt::format("warning: rgbd: {} more acquisitions left out (see {})",
                                    listed - kListed, o.output.string()));
  if (report.failed > 0 && report.done + report.skipped == 0) {
    const RgbdAcquisitionResult* first = report.FirstFailure();
    o.details.clear();  // the error names the first failure and the report that lists them all
    o.ok = false;
    // What the inputs showed (a pattern matrix that cannot decode) often says why: it leads.
    const std::string cause = report.warnings.empty() ? "" : "; " + report.warnings.front();
    o.error = fmt::format(
        "no acquisition could be processed: all {} failed{} (first failure: {}: {}; see {})",
        report.failed, cause, first->file, first->reason, o.output.string());
  } else if (report.acquisitions == 0) {
    o.ok = false;
    o.error = "the run has no acquisition";
  }
  return o;
}

StageOutcome RegisterOutcome(const RegisterStageReport& report,
                             const std::filesystem::path& workspace) {
  StageOutcome o;
  const std::filesystem::path folder = workspace / "registration";
  o.output = folder / "poses.csv";
  o.summary = fmt::format(
      "register: {} acquisitions, {} nodes, {} left out; {} pairs ({} registered now, {} from an "
      "earlier run): {} feature, {} projection ({} with texture, {} degenerate), {} failed; {} "
      "rig/odometry/straightness edges; {} rejected by the gate; {:.1f} s ({:.2f} s per pair)",
      report.acquisitions, report.nodes, report.left_out.size(), report.pairs, report.pairs_done,
      report.pairs_skipped, report.feature_edges, report.projection_edges, report.textured_edges,
      report.degenerate_edges, report.pairs_failed, report.prior_edges, report.fusion.rejected,
      report.seconds, report.seconds_per_pair);
  for (const std::string& w : report.odometry_warnings) o.details.push_back("warning: " + w);
  for (const std::string& w : report.rig_warnings) o.details.push_back("warning: " + w);
  for (const std::string& w : report.graph_warnings) o.details.push_back("warning: " + w);
  for (const LeftOutAcquisition& l : report.left_out)
    o.details.push_back(fmt::format("left out: m{} counter {}: {}", l.module, l.counter, l.reason));
  if (report.nodes == 0) {
    o.ok = false;
    o.error =
        fmt::format("no acquisition with depth to register: {} of {} left out{}",
                    report.left_out.size(), report.acquisitions,
                    report.left_out.empty() ? "" : " (first: " + report.left_out[0].reason + ")");
  } else if (!report.fusion.usable) {
    o.ok = false;
    o.error =
        fmt::format("the pose graph did not converge (see {})", (folder / "report.json").string());
  }
  return o;
}

StageOutcome ModelOutcome(const ModelStageReport& r, const std::filesystem::path& workspace) {
  StageOutcome o;
  o.output = workspace / "model" / "preview.png";
  if (!r.ok) {
    o.ok = false;
    o.summary = fmt::format("model: {} acquisitions; no model", r.acquisitions);
    o.error = fmt::format("{}: {}", (workspace / "model").string(), r.message);
    return o;
  }
  const CentrelineFitReport& c = r.centreline;
  o.summary = fmt::format(
      "model: {} acquisitions; centreline from {}/{} slices, fitted diameter {:.2f} mm (model "
      "{:.0f} mm){}; maps {} x {} cells at {} mm ({} tiles, {} from an earlier run), {:.1f} % "
      "measured, {:.1f} % filled; mesh.glb {} vertices at {:.1f} mm; {:.1f} s ({:.2f} s per "
      "acquisition)",
      r.acquisitions, c.slices_used, c.slices_used + c.slices_rejected, 2.0 * c.radius_mm,
      r.nominal_diameter_mm,
      c.bend_radius_mm ? fmt::format(", bend radius {:.1f} m", *c.bend_radius_mm / 1000.0) : "",
      r.grid.rows, r.grid.cols, r.grid.resolution_mm, r.tiles, r.tiles_from_earlier_run,
      100.0 * r.measured_fraction, 100.0 * r.filled_fraction, r.displaced_vertices,
      r.displaced_step_mm, r.seconds, r.seconds_per_acquisition);
  const ModuleOffsets& m = r.module_offsets;
  if (m.estimated) {
    const auto [lo, hi] = std::minmax_element(m.range_mm.begin(), m.range_mm.end());
    o.details.push_back(fmt::format(
        "model: module range offsets {:+.3f} … {:+.3f} mm from {} seam cells (their RMS {:.3f} "
        "→ {:.3f} mm)",
        *lo, *hi, m.cells, m.rms_before_mm, m.rms_after_mm));
  } else {
    o.details.push_back("model: no module range offsets: " + m.why);
  }
  for (const std::string& w : r.warnings) o.details.push_back("warning: model: " + w);
  return o;
}

StageOutcome InspectOutcome(const InspectStageReport& r, const std::filesystem::path& workspace) {
  StageOutcome o;
  o.output = workspace / "inspection" / "observations.csv";
  std::string codes;
  for (const auto& [code, n] : r.per_code)
    codes += fmt::format("{}{} {}", codes.empty() ? "" : ", ", n, code);
  // No ring measured all round: no inspected stations (NaN) to print.
  const std::string stations =
      std::isfinite(r.inspected_from_mm)
          ? fmt::format("stations {:.0f}..{:.0f} mm inspected", r.inspected_from_mm,
                        r.inspected_to_mm)
          : std::string("no station inspected (no ring of the wall measured all round)");
  const std::string noise = std::isfinite(r.inspected_from_mm)
                                ? fmt::format("{:.3f} mm", r.inspection.residual_sigma_mm)
                                : std::string("not measured");
  o.summary = fmt::format(
      "inspect: {} observations{}; {} ({:.0f} % of the map), wall noise {}; profile {} rows ({} "
      "measured all round); {:.1f} s",
      r.observations, codes.empty() ? "" : " (" + codes + ")", stations,
      100.0 * r.inspection.inspected_share, noise, r.profile_rows, r.profile_rows_measured,
      r.seconds);
  return o;
}

StageOutcome ReportOutcome(const ReportStageReport& r) {
  StageOutcome o;
  o.output = r.html;
  const ReportSummary& s = r.summary;
  o.summary = fmt::format(
      "report: {:.1f} MB; maps {}, 3D viewer {}, {} observations, profile {}; {:.1f} s",
      static_cast<double>(s.html_bytes) / 1e6, s.maps ? "yes" : "no", s.viewer ? "yes" : "no",
      r.observations >= 0 ? std::to_string(r.observations) : "no",
      r.profile_rows >= 0 ? std::to_string(r.profile_rows) + " rows" : "no", r.seconds);
  for (const std::string& note : s.notes) o.details.push_back("note: " + note);
  if (!s.maps_problem.empty())
    o.details.push_back("warning: report without maps: " + s.maps_problem);
  return o;
}

}  // namespace sewer3d
