#include "sewer3d/pipeline/process_chain.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/pipeline/rgbd_inputs.hpp"

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
          },
          "rgbd/report.json",
          [](const CaptureRun& run, const Workspace& ws) {
            return RgbdUpToDate(run, ws.StageFolder("rgbd"));
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
      },
      "registration/poses.csv", nullptr};
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
          },
          "model/model.json",
          [](const CaptureRun&, const Workspace& ws) {
            return ModelFilesPresent(ws.StageFolder("model"));
          }};
}

ProcessStage InspectProcessStage() {
  auto stage_options = [](const ProcessOptions& o) {
    InspectStageOptions i = o.inspect;
    i.force = o.force;
    return i;
  };
  return {"inspect", [=](const ProcessOptions& o) { return InspectOptionsJson(stage_options(o)); },
          [=](const CaptureRun& run, Workspace& ws, const ProcessOptions& o,
              const StageProgress& progress) {
            return InspectOutcome(RunInspectStage(run, ws, stage_options(o), progress),
                                  ws.folder());
          },
          "inspection/observations.json", nullptr};
}

ProcessStage ReportProcessStage() {
  return {"report", [](const ProcessOptions&) { return std::string("{}"); },
          [](const CaptureRun& run, Workspace& ws, const ProcessOptions& o, const StageProgress&) {
            return ReportOutcome(RunReportStage(run, ws, o.force));
          },
          "report/index.html", nullptr};
}

// Recorded done with the options it would run with now, nothing before it changed, its main
// output still on disk (a stage folder removed by hand is made again) and its inputs as it
// left them (up_to_date).
bool CanSkip(const CaptureRun& run, const Workspace& workspace, const ProcessStage& stage,
             const std::string& options) {
  const auto it = workspace.record().stages.find(stage.name);
  std::error_code ec;
  return it != workspace.record().stages.end() && it->second.done &&
         it->second.options_json == options &&
         std::filesystem::is_regular_file(workspace.folder() / stage.output, ec) &&
         (!stage.up_to_date || stage.up_to_date(run, workspace));
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
  SEWER3D_VALIDATE(resolution_mm <= inspect.inspect.max_map_cell_mm, "resolution_mm",
                   "must be ≤ " << inspect.inspect.max_map_cell_mm
                                << " mm for the inspection (cracks and joint gaps are a few mm "
                                   "wide), got "
                                << resolution_mm
                                << "; a coarser model alone: `sewer3d model --resolution-mm`");
  SEWER3D_VALIDATE(threads >= 1, "threads", "must be at least 1, got " << threads);
  rgbd.Check();
  registration.Check();
  model.Check();
  inspect.Check();
}

const std::vector<ProcessStage>& ProcessStages() {
  static const std::vector<ProcessStage> stages = {RgbdProcessStage(), RegisterProcessStage(),
                                                   ModelProcessStage(), InspectProcessStage(),
                                                   ReportProcessStage()};
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
        CanSkip(run, workspace, stage, stage.options_json(options))) {
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
