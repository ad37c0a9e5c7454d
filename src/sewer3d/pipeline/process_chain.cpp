#include "sewer3d/pipeline/process_chain.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

using Clock = std::chrono::steady_clock;

ProcessStage RgbdProcessStage() {
  auto stage_options = [](const ProcessOptions& o) {
    RgbdStageOptions r = o.rgbd;
    r.threads = o.threads;
    r.force = o.force;
    return r;
  };
  return {"rgbd", [=](const ProcessOptions& o) { return RgbdOptionsJson(stage_options(o)); },
          [=](const CaptureRun& run, Workspace& ws, const ProcessOptions& o,
              const StageProgress& progress) {
            return RgbdOutcome(RunRgbdStage(run, ws, stage_options(o), progress), ws.folder());
          }};
}

ProcessStage RegisterProcessStage() {
  auto stage_options = [](const ProcessOptions& o) {
    RegisterStageOptions r = o.registration;
    r.threads = o.threads;
    r.fusion.threads = o.threads;
    r.force = o.force;
    return r;
  };
  return {
      "register", [=](const ProcessOptions& o) { return RegisterOptionsJson(stage_options(o)); },
      [=](const CaptureRun& run, Workspace& ws, const ProcessOptions& o,
          const StageProgress& progress) {
        return RegisterOutcome(RunRegisterStage(run, ws, stage_options(o), progress), ws.folder());
      }};
}

ProcessStage ModelProcessStage() {
  auto stage_options = [](const ProcessOptions& o) {
    ModelStageOptions m = o.model;
    m.resolution_mm = o.resolution_mm;
    m.start_station_mm = o.start_station_mm;
    m.threads = o.threads;
    m.force = o.force;
    return m;
  };
  return {"model", [=](const ProcessOptions& o) { return ModelOptionsJson(stage_options(o)); },
          [=](const CaptureRun& run, Workspace& ws, const ProcessOptions& o,
              const StageProgress& progress) {
            return ModelOutcome(RunModelStage(run, ws, stage_options(o), progress), ws.folder());
          }};
}

// Recorded done with the options it would run with now, and nothing before it changed.
bool CanSkip(const Workspace& workspace, const std::string& stage, const std::string& options) {
  const auto it = workspace.record().stages.find(stage);
  return it != workspace.record().stages.end() && it->second.done &&
         it->second.options_json == options;
}

std::string StageNames() {
  std::string names;
  for (const ProcessStage& s : ProcessStages()) names += (names.empty() ? "" : " ") + s.name;
  return names;
}

}  // namespace

void ProcessOptions::Check() const {
  SEWER3D_VALIDATE(std::isfinite(start_station_mm), "start_station_mm", "must be finite");
  SEWER3D_VALIDATE(std::isfinite(resolution_mm) && resolution_mm >= 0.01 && resolution_mm <= 50.0,
                   "resolution_mm", "must be 0.01..50 mm, got " << resolution_mm);
  SEWER3D_VALIDATE(threads >= 1, "threads", "must be at least 1, got " << threads);
  rgbd.Check();
  registration.Check();
  model.Check();
}

StageOutcome RgbdOutcome(const RgbdStageReport& report, const std::filesystem::path& workspace) {
  StageOutcome o;
  o.output = workspace / "rgbd" / "report.json";
  o.summary = fmt::format(
      "rgbd: {} acquisitions: {} done, {} skipped (done before), {} failed; {} points; "
      "{:.2f} s per acquisition, {:.1f} s in all ({} threads); colour: {}",
      report.acquisitions, report.done, report.skipped, report.failed, report.points,
      report.seconds_per_acquisition, report.seconds, report.threads, kRgbdColorSource);
  if (const RgbdAcquisitionResult* first = report.FirstFailure()) {
    o.ok = false;
    o.error = fmt::format("{}: {}; {} of {} acquisitions failed (see {})", first->file,
                          first->reason, report.failed, report.acquisitions, o.output.string());
  }
  return o;
}

StageOutcome RegisterOutcome(const RegisterStageReport& report,
                             const std::filesystem::path& workspace) {
  StageOutcome o;
  const std::filesystem::path folder = workspace / "registration";
  o.output = folder / "poses.csv";
  o.summary = fmt::format(
      "register: {} acquisitions, {} nodes, {} left out; {} pairs ({} done, {} from an earlier "
      "run, {} failed): {} feature, {} projection ({} degenerate); {} rig/odometry/straightness "
      "edges; {} rejected by the gate; {:.1f} s ({:.2f} s per pair)",
      report.acquisitions, report.nodes, report.left_out.size(), report.pairs, report.pairs_done,
      report.pairs_skipped, report.pairs_failed, report.feature_edges, report.projection_edges,
      report.degenerate_edges, report.prior_edges, report.fusion.rejected, report.seconds,
      report.seconds_per_pair);
  for (const LeftOutAcquisition& l : report.left_out)
    o.details.push_back(fmt::format("left out: m{} counter {}: {}", l.module, l.counter, l.reason));
  if (!report.fusion.usable) {
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
  return o;
}

const std::vector<ProcessStage>& ProcessStages() {
  static const std::vector<ProcessStage> stages = {RgbdProcessStage(), RegisterProcessStage(),
                                                   ModelProcessStage()};
  return stages;
}

const ProcessStageResult* ProcessReport::Failure() const {
  for (const ProcessStageResult& s : stages) {
    if (!s.outcome.ok) return &s;
  }
  return nullptr;
}

std::string ProcessOptionsJson(const ProcessOptions& options) {
  nlohmann::json names = nlohmann::json::array();
  for (const ProcessStage& s : ProcessStages()) names.push_back(s.name);
  const nlohmann::json j = {{"resolution_mm", options.resolution_mm},
                            {"start_station_mm", options.start_station_mm},
                            {"stages", names}};
  return j.dump();
}

ProcessReport RunProcess(const CaptureRun& run, Workspace& workspace, const ProcessOptions& options,
                         const StageProgress& progress, const StageFinished& finished) {
  options.Check();
  const auto start = Clock::now();
  const std::string options_json = ProcessOptionsJson(options);
  workspace.RecordCommand("process", options_json, false, 0.0, {{"stages", StageNames()}});
  ProcessReport report;
  std::string skipped;
  bool upstream_unchanged = true;
  for (const ProcessStage& stage : ProcessStages()) {
    ProcessStageResult r;
    r.name = stage.name;
    const auto stage_start = Clock::now();
    if (!options.force && upstream_unchanged &&
        CanSkip(workspace, stage.name, stage.options_json(options))) {
      r.skipped = true;
      r.seconds = workspace.record().stages.at(stage.name).seconds;
      r.outcome.summary = stage.name + ": done before with these options (workspace.json); skipped";
      skipped += (skipped.empty() ? "" : " ") + stage.name;
    } else {
      upstream_unchanged = false;
      r.outcome =
          stage.run(run, workspace, options, [&](const std::string& pass, int done, int total) {
            if (progress) progress(stage.name + " " + pass, done, total);
          });
      r.seconds = std::chrono::duration<double>(Clock::now() - stage_start).count();
    }
    report.stages.push_back(r);
    if (finished) finished(r);
    if (!r.outcome.ok) break;
  }
  report.ok = report.Failure() == nullptr;
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::map<std::string, std::string> notes = {{"stages", StageNames()}, {"skipped", skipped}};
  if (const ProcessStageResult* failed = report.Failure()) notes["failed"] = failed->name;
  workspace.RecordCommand("process", options_json, report.ok, report.seconds, notes);
  return report;
}

}  // namespace sewer3d
