#include "sewer3d/pipeline/rgbd_stage.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/camera/module.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/pattern/constraints.hpp"
#include "sewer3d/pipeline/acquisition_images.hpp"
#include "sewer3d/pipeline/parallel_items.hpp"
#include "sewer3d/pipeline/rgbd_inputs.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;
using Status = RgbdAcquisitionResult::Status;
constexpr const char* kStage = "rgbd";

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

const char* StatusName(Status status) {
  switch (status) {
    case Status::kDone:
      return "done";
    case Status::kSkipped:
      return "skipped";
    case Status::kFailed:
      return "failed";
  }
  return "?";
}

json DecoderOptionsJson(const DecoderOptions& d) {
  json niblack = {
      {"window", d.niblack.window}, {"k", d.niblack.k}, {"min_contrast", d.niblack.min_contrast}};
  // Only when used (--faint-spots): workspaces from before the option stay resumable.
  if (d.niblack.min_contrast_3x3 > 0.0) niblack["min_contrast_3x3"] = d.niblack.min_contrast_3x3;
  return {{"niblack", niblack},
          {"spots",
           {{"min_area_px", d.spots.min_area_px},
            {"max_area_px", d.spots.max_area_px},
            {"max_aspect", d.spots.max_aspect}}},
          {"lattice",
           {{"max_neighbour_px", d.lattice.max_neighbour_px},
            {"max_residual", d.lattice.max_residual},
            {"max_edge_steps", d.lattice.max_edge_steps}}},
          {"codewords",
           {{"min_votes", d.codewords.min_votes},
            {"min_agreement", d.codewords.min_agreement},
            {"border_px", d.codewords.border_px}}},
          {"prediction_depth_mm", d.prediction_depth_mm}};
}

json CutSpotOptionsJson(const CutSpotOptions& o) {
  if (!o.enabled) return {{"enabled", false}};
  return {{"enabled", true},
          {"max_fit_px", o.max_fit_px},
          {"max_fit_tolerance", o.max_fit_tolerance},
          {"min_neighbours", o.min_neighbours},
          {"area_fraction", o.area_fraction}};
}

json LostSpotOptionsJson(const LostSpotOptions& o) {
  if (!o.enabled) return {{"enabled", false}};
  return {{"enabled", true},
          {"min_neighbours", o.min_neighbours},
          {"max_fit_px", o.max_fit_px},
          {"max_fit_tolerance", o.max_fit_tolerance},
          {"step_fits", o.step_fits},
          {"max_offset", o.max_offset},
          {"max_rounds", o.max_rounds},
          {"min_sigmas", o.spot.min_sigmas},
          {"min_levels", o.spot.min_levels},
          {"min_noise_levels", o.spot.min_noise_levels}};
}

std::vector<PatternConstraints> RigConstraints(const CaptureRun& run) {
  std::vector<PatternConstraints> constraints;
  for (size_t k = 0; k < run.patterns.size(); ++k) {
    try {
      constraints.push_back(InferConstraints(run.patterns[k]));
    } catch (const std::invalid_argument& e) {
      throw FileError(run.folder / "rig.json", "module m" + std::to_string(k) +
                                                   ": cannot decode with its pattern: " + e.what());
    }
    // A matrix replaced since the module was designed (too few columns for its disparity) would
    // fail every acquisition as if the images were wrong.
    const ModuleDescription& module = run.rig.modules[k].module;
    const int step = std::max(1, std::max(module.camera.width, module.camera.height) / 64);
    const DisparityRange range =
        ComputeDisparityRange(module, kWorkingDistanceMinMm, kWorkingDistanceMaxMm, step);
    const BinaryArray& pattern = run.patterns[k];
    if (const std::string problem = PatternSpanProblem(range, pattern.rows, pattern.cols);
        !problem.empty()) {
      throw FileError(run.folder / "rig.json", "module " + run.rig.modules[k].name + " (" +
                                                   run.rig.modules[k].module.pattern.matrix_path +
                                                   "): " + problem);
    }
  }
  return constraints;
}

// Spots and points of a complete acquisition, from its report (also for those done before).
void ReadTotals(const std::filesystem::path& rgbd_folder, RgbdAcquisitionSummary& s) {
  const RgbdFiles files = RgbdAcquisitionFiles(rgbd_folder, s.module, s.counter);
  s.complete = RgbdAcquisitionDone(files);
  if (!s.complete) return;
  const json report = json::parse(ReadTextFile(files.report), nullptr, false);
  if (report.is_discarded() || !report.is_object())
    throw FileError(files.report, "not a JSON object: remove it to redo the acquisition");
  s.spots = report.value("spots_found", 0LL);
  s.points = report.value("points", 0LL);
  if (report.contains("warnings") && report["warnings"].is_array()) {
    for (const json& w : report["warnings"])
      if (w.is_string()) s.warnings.push_back(w.get<std::string>());
  }
  const json deblur = report.value("color_steps", json::object()).value("deblur", json());
  s.without_odometry = deblur.is_string() && deblur.get<std::string>().rfind("not done", 0) == 0;
}

// Acquisitions the colour pass could not deblur (no odometry reading around their time): the
// summary says so, and one warning counts them.
void NoteUndeblurred(const RgbdColourOptions& options, RgbdStageReport& report) {
  const auto n = std::count_if(report.results.begin(), report.results.end(),
                               [](const RgbdAcquisitionSummary& s) { return s.without_odometry; });
  if (n == 0) return;
  const auto complete = std::count_if(report.results.begin(), report.results.end(),
                                      [](const RgbdAcquisitionSummary& s) { return s.complete; });
  report.warnings.push_back(fmt::format(
      "{} of {} acquisitions not deblurred and their texture triplets mapped without motion: "
      "odometry.csv gives no distance around their images' times",
      n, complete));
  report.color_source = RgbdColorSource(
      options, fmt::format("for {} of {}: no odometry for the others", complete - n, complete));
}

void Summarise(RgbdStageReport& report) {
  for (const RgbdAcquisitionSummary& s : report.results) {
    if (s.Failure() != nullptr) {
      ++report.failed;
    } else if (s.colour.status == Status::kDone) {
      ++report.done;
      const double seconds = s.geometry.seconds + s.colour.seconds;
      report.seconds_per_acquisition += seconds;
      report.max_seconds_per_acquisition = std::max(report.max_seconds_per_acquisition, seconds);
    } else {
      ++report.skipped;
    }
    report.spots += s.spots;
    report.points += s.points;
  }
  if (report.done > 0) report.seconds_per_acquisition /= report.done;
}

json GainsJson(const ModuleGains& gains) {
  json list = json::array();
  for (const cv::Vec3d& g : gains.gains_bgr) list.push_back({g[0], g[1], g[2]});
  return list;
}

json PassJson(const RgbdAcquisitionResult& r) {
  json j = {{"status", StatusName(r.status)}};
  if (r.status == Status::kDone) j["seconds"] = r.seconds;
  return j;
}

}  // namespace

void RgbdStageOptions::Check() const {
  reconstruction.Check();
  colour.Check();
  SEWER3D_VALIDATE(threads >= 1, "threads", "must be at least 1, got " << threads);
}

std::string RgbdOptionsJson(const RgbdStageOptions& options) {
  const FrameReconstructionOptions& r = options.reconstruction;
  const json j = {{"decoder", DecoderOptionsJson(r.decoder)},
                  {"max_edge_steps", r.max_edge_steps},
                  {"triangulation",
                   {{"z_min_mm", r.triangulation.z_min_mm},
                    {"z_max_mm", r.triangulation.z_max_mm},
                    {"max_reprojection_px", r.triangulation.max_reprojection_px}}},
                  {"outliers",
                   {{"radius_px", r.outliers.radius_px},
                    {"min_step_mm", r.outliers.min_step_mm},
                    {"fraction", r.outliers.fraction}}},
                  {"cut_spots", CutSpotOptionsJson(r.cut_spots)},
                  {"lost_spots", LostSpotOptionsJson(r.lost_spots)},
                  {"color", RgbdColorSource(options.colour)},
                  {"colour", json::parse(RgbdColourOptionsJson(options.colour))}};
  return j.dump();
}

const RgbdAcquisitionResult* RgbdAcquisitionSummary::Failure() const {
  if (geometry.status == Status::kFailed) return &geometry;
  if (colour.status == Status::kFailed) return &colour;
  return nullptr;
}

const RgbdAcquisitionResult* RgbdStageReport::FirstFailure() const {
  for (const RgbdAcquisitionSummary& s : results) {
    if (const RgbdAcquisitionResult* f = s.Failure()) return f;
  }
  return nullptr;
}

std::string RgbdStageReportToJson(const RgbdStageReport& report) {
  json failures = json::array(), list = json::array();
  for (const RgbdAcquisitionSummary& s : report.results) {
    json entry = {{"module", s.module},
                  {"counter", s.counter},
                  {"complete", s.complete},
                  {"geometry", PassJson(s.geometry)},
                  {"colour", PassJson(s.colour)}};
    if (const RgbdAcquisitionResult* f = s.Failure()) {
      failures.push_back(
          {{"module", s.module}, {"counter", s.counter}, {"file", f->file}, {"reason", f->reason}});
    }
    if (s.complete) {
      entry["spots"] = s.spots;
      entry["points"] = s.points;
    }
    list.push_back(entry);
  }
  json references = json::array();
  for (const RgbdReferenceResult& r : report.references) {
    json entry = {{"module", r.module},
                  {"estimated", r.reference.has_value()},
                  {"from_earlier_run", r.skipped}};
    if (!r.skipped) {
      entry["frames"] = r.report.frames;
      entry["cells_filled"] = r.report.cells_filled;
      entry["cells"] = r.report.cells;
    }
    if (!r.reason.empty()) entry["reason"] = r.reason;
    references.push_back(entry);
  }
  const json j = {
      {"stage", kStage},
      {"color", report.color_source},
      {"references", references},
      {"module_gains",
       {{"seams", report.module_gains.seams},
        {"rms_log_residual", report.module_gains.rms_log_residual},
        {"gains_bgr", GainsJson(report.module_gains)}}},
      {"wall_colour_bgr",
       {report.wall_colour_bgr[0], report.wall_colour_bgr[1], report.wall_colour_bgr[2]}},
      {"acquisitions", report.acquisitions},
      {"warnings", report.warnings},
      {"done", report.done},
      {"skipped", report.skipped},
      {"failed", report.failed},
      {"failures", failures},
      {"totals", {{"spots", report.spots}, {"points", report.points}}},
      {"seconds",
       {{"stage", report.seconds},
        {"per_acquisition_mean", report.seconds_per_acquisition},
        {"per_acquisition_max", report.max_seconds_per_acquisition}}},
      {"threads", report.threads},
      {"per_acquisition", list}};
  return j.dump(2) + "\n";
}

RgbdStageReport RunRgbdStage(const CaptureRun& run, Workspace& workspace,
                             const RgbdStageOptions& options, const StageProgress& progress) {
  options.Check();
  SEWER3D_CHECK(
      run.patterns.size() == run.rig.modules.size(),
      "one pattern per module: " << run.patterns.size() << " for " << run.rig.modules.size());
  const auto start = Clock::now();
  const std::vector<PatternConstraints> constraints = RigConstraints(run);
  CheckRigMatchesImages(run);
  workspace.BeginStage(kStage, RgbdOptionsJson(options), options.force);
  const std::filesystem::path folder = workspace.StageFolder(kStage);
  const std::vector<Acquisition> acquisitions = GroupAcquisitions(run.images);
  const int total = static_cast<int>(acquisitions.size());

  RgbdStageReport report;
  report.warnings = PatternMatrixWarnings(run, constraints);
  for (std::string& line : ForgetChangedAcquisitions(run, acquisitions, folder))
    report.warnings.push_back(std::move(line));
  report.acquisitions = total;
  report.threads = options.threads;
  report.color_source = RgbdColorSource(options.colour);
  report.results.resize(acquisitions.size());
  auto progress_of = [&](const std::string& pass) {
    return [&progress, pass, total](int finished) {
      if (progress) progress(pass, finished, total);
    };
  };
  ForEachItem<Reconstructors>(
      acquisitions.size(), options.threads,
      [&] { return Reconstructors(run, constraints, options.reconstruction); },
      [&](size_t i, Reconstructors& reconstructors) {
        RgbdAcquisitionSummary& s = report.results[i];
        s.module = acquisitions[i].module;
        s.counter = acquisitions[i].counter;
        s.geometry = RgbdGeometryPass(run, acquisitions[i], folder, reconstructors);
      },
      progress_of("geometry"));
  for (std::string& line : RepeatedImageWarnings(run, acquisitions, folder))
    report.warnings.push_back(std::move(line));
  const size_t modules = run.rig.modules.size();
  report.references.resize(modules);
  ForEachItem<int>(
      modules, options.threads, [] { return 0; },
      [&](size_t k, int&) {
        report.references[k] =
            RgbdReferencePass(run, static_cast<int>(k), acquisitions, folder, options.colour);
      },
      [&](int finished) {
        if (progress) progress("reference", finished, static_cast<int>(modules));
      });
  // Every module's median wall is given the modules' common colour (CommonWallColour).
  CorrectionOptions correction = options.colour.correction;
  std::vector<cv::Vec3d> levels;
  for (RgbdReferenceResult& r : report.references) {
    if (!r.reference) continue;
    const cv::Vec3d& level = r.reference->level_bgr;
    const auto usable = [](double x) { return x > 0.0 && std::isfinite(x); };
    if (!(usable(level[0]) && usable(level[1]) && usable(level[2]))) {
      // A black (or unbounded) channel: the points the reference was fitted on do not lie on the
      // lit wall (a rig whose camera does not match its images, or no light): the module goes
      // uncorrected.
      r.reference.reset();
      r.file = (run.folder / "rig.json").string();
      r.reason = fmt::format(
          "the reference wall level is ({:.3g}, {:.3g}, {:.3g}) (B, G, R), not a light level: do "
          "the rig's camera parameters match the images?",
          level[0], level[1], level[2]);
      continue;
    }
    levels.push_back(level);
  }
  if (!levels.empty())
    correction.target_bgr = CommonWallColour(levels, correction.wall_level_linear);
  report.wall_colour_bgr = correction.target_bgr;
  std::vector<std::unique_ptr<ShadingCorrector>> correctors(modules);
  ForEachItem<int>(
      modules, options.threads, [] { return 0; },
      [&](size_t k, int&) {
        if (!report.references[k].reference) return;
        correctors[k] =
            std::make_unique<ShadingCorrector>(CameraModel(run.rig.modules[k].module.camera),
                                               *report.references[k].reference, correction);
      },
      {});
  std::vector<const ShadingCorrector*> corrector_list;
  for (const auto& c : correctors) corrector_list.push_back(c.get());
  report.module_gains = RgbdSeamPass(run, acquisitions, folder, corrector_list, options.colour);
  ForEachItem<int>(
      acquisitions.size(), options.threads, [] { return 0; },
      [&](size_t i, int&) {
        RgbdAcquisitionSummary& s = report.results[i];
        if (s.geometry.status == Status::kFailed) {
          s.colour.status = Status::kSkipped;
          return;
        }
        const int m = acquisitions[i].module;
        s.colour = RgbdColourPass(run, acquisitions[i], folder, correctors[m].get(),
                                  report.module_gains.gains_bgr[m], options.colour);
        // Without a reference light, the reason it could not be made is the one to read.
        const RgbdReferenceResult& ref = report.references[m];
        if (correctors[m] == nullptr && s.colour.status == Status::kFailed && !ref.reason.empty())
          FailAcquisition(s.colour, ref.file.empty() ? s.colour.file : ref.file,
                          "module m" + std::to_string(m) + ": " + ref.reason);
      },
      progress_of("colour"));

  for (RgbdAcquisitionSummary& s : report.results) {
    ReadTotals(folder, s);
    for (const std::string& line : s.warnings) report.warnings.push_back(line);
  }
  NoteUndeblurred(options.colour, report);
  Summarise(report);
  report.seconds = SecondsSince(start);
  WriteTextFileAtomically(folder / "report.json", RgbdStageReportToJson(report));
  workspace.FinishStage(kStage, report.failed == 0,
                        {{"color", report.color_source},
                         {"acquisitions", std::to_string(report.acquisitions)},
                         {"failed", std::to_string(report.failed)}},
                        /*changed=*/report.done > 0 || report.failed > 0);
  return report;
}

}  // namespace sewer3d
