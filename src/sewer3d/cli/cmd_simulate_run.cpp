// `sewer3d simulate run`: a whole inspection run from a scenario or a preset (docs/formats.md).

#include <fmt/core.h>

#include <cstdio>
#include <filesystem>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/progress_bar.hpp"
#include "sewer3d/cli/simulate_commands.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/spot_errors.hpp"
#include "sewer3d/simio/scenario_io.hpp"
#include "sewer3d/simio/simulate_run.hpp"

namespace sewer3d::cli {

CLI::App* AddRunCommand(CLI::App& sim, RunArgs& a) {
  CLI::App* run = sim.add_subcommand(
      "run", "Simulate a whole inspection run: six modules, robot motion, odometry, truth");
  auto* scenario = run->add_option("--scenario", a.scenario, "Scenario JSON file (docs/formats.md)")
                       ->check(CLI::ExistingFile);
  auto* preset =
      run->add_option("--preset", a.preset, "Built-in scenario: tiny, compact, demo or long")
          ->check(CLI::IsMember(PresetNames()));
  scenario->excludes(preset);
  run->add_option("--out", a.out, "Run folder to write")->required();
  run->add_option("--seed", a.seed, "Seed (overrides the scenario's)")->check(Digits());
  run->add_option("--module", a.module, "Module file for every module (overrides the scenario's)")
      ->check(CLI::ExistingFile);
  run->add_option("--supersampling", a.supersampling,
                  "S x S samples per pixel (overrides the scenario's)")
      ->check(CLI::Range(1, 16));
  run->add_option("--realism", a.realism,
                  "Error sources of real modules and walls, over the scenario's: ideal (none) or "
                  "paper (the scenarios' default: docs/simulator.md, \"Error sources\")")
      ->check(CLI::IsMember({"ideal", "paper"}));
  run->add_flag("--quiet", a.quiet, "No progress bar");
  run->add_flag("--restart", a.restart,
                "Render every image again; without it, an interrupted simulation of the same run "
                "in --out keeps the images it finished");
  run->add_flag("--allow-large", a.allow_large,
                "Run even when the plan exceeds 200 000 images, 20 M odometry rows or the free "
                "disk space");
  return run;
}

int RunRun(const RunArgs& a) {
  if (a.scenario.empty() && a.preset.empty()) {
    std::fprintf(stderr, "sewer3d: error: simulate run needs --scenario FILE or --preset NAME\n");
    return 2;
  }
  Scenario s = a.scenario.empty() ? PresetScenario(a.preset) : ReadScenario(a.scenario);
  if (a.seed != 0) s.seed = a.seed;
  if (a.supersampling != 0) s.render.supersampling = a.supersampling;
  if (!a.realism.empty()) s.render.spot_errors = *RealismProfile(a.realism);
  std::filesystem::path module_file = a.module;
  if (module_file.empty() && !s.module_file.empty()) {
    module_file = std::filesystem::path(a.scenario).parent_path() / s.module_file;
  }
  ModuleDescription module;
  BinaryArray pattern;
  if (!module_file.empty()) {
    LoadedModule loaded = LoadModule(module_file);
    module = loaded.module;
    pattern = loaded.pattern;
    if (!a.scenario.empty() && s.camera_width != module.camera.width) {
      fmt::print(stderr,
                 "sewer3d: warning: {}: camera_width {} not used: the module {} has its own "
                 "camera, {} px wide\n",
                 a.scenario, s.camera_width, module_file.string(), module.camera.width);
      s.camera_width = module.camera.width;
    }
    s.module_file = ModuleFileFromTruth(a.out, module_file);
  } else {
    DefaultModuleOptions options;
    options.camera_width = s.camera_width;
    options.camera_height = s.camera_width * 3 / 4;
    module = MakeDefaultModule(options);
    pattern = DefaultPatternArray();
  }
  ProgressBar bar(a.quiet);
  auto progress = [&](int done, int total) {
    bar.Update("simulate " + s.name, done, total, "images");
  };
  // What only the simulation can check (the rig's fit, the capture plan) is still the scenario
  // file's error.
  SimulatedRun r;
  RunSizeEstimate size;
  auto estimate = [&] { size = EstimateRunSize(s, module); };
  auto simulate = [&] { r = SimulateRun(s, module, pattern, a.out, progress, a.restart); };
  const auto in_scenario = [&](const auto& step) {
    if (a.scenario.empty())
      step();
    else
      ValidateFileContents(a.scenario, step);
  };
  in_scenario(estimate);
  if (!a.allow_large) {
    // The folder first, so that its own file system is asked for free space and a folder that
    // cannot be made is named as such; a refused run leaves no new folder behind.
    std::error_code ec;
    const bool existed = std::filesystem::exists(a.out, ec);
    std::filesystem::create_directories(a.out, ec);
    if (ec) throw FileError(a.out, "cannot create the folder: " + ec.message());
    try {
      CheckRunFits(size, a.out);
    } catch (const InvalidValue& e) {
      if (!existed) std::filesystem::remove(a.out, ec);
      throw InvalidValue("", e.problem() + " (--allow-large runs it anyway)");
    }
  }
  // The plan before the work: rendering time grows with the image size and the square of the
  // supersampling.
  const int ss = s.render.supersampling;
  fmt::print(
      "simulate '{}': {} images of {}x{} px at {}x{} samples per pixel ({:.2g} samples in "
      "all), about {:.1f} MB\n",
      s.name, size.images, module.camera.width, module.camera.height, ss, ss,
      static_cast<double>(size.images) * module.camera.width * module.camera.height * ss * ss,
      size.bytes / 1e6);
  std::fflush(stdout);
  in_scenario(simulate);
  fmt::print("run '{}': {} acquisitions x {} modules x 3 images = {} images of {}x{} px\n", s.name,
             r.plan.acquisitions, s.rig.modules, r.images, module.camera.width,
             module.camera.height);
  fmt::print(
      "robot: {:.0f} mm at {:.0f} mm/s in {:.2f} s; acquisition every {:.3f} s ({:.0f} mm "
      "footprint, {:.0f} % overlap)\n",
      s.motion.travel_mm, s.motion.speed_mm_s, r.duration_s, r.plan.period_s, r.plan.footprint_mm,
      100.0 * s.capture.overlap);
  std::string overlap;
  for (const NeighbourOverlap& o : r.overlap)
    overlap += fmt::format(" m{}-m{} {:.1f} deg", o.module, o.next, o.overlap_deg);
  fmt::print("neighbour overlap (3-D, DN{:.0f}, centred):{}\n", s.capture.nominal_diameter_mm,
             overlap);
  std::string kept;
  if (r.images_kept > 0)
    kept = fmt::format("; {} of {} images kept (--restart renders all)", r.images_kept, r.images);
  fmt::print("wrote {} ({:.1f} MB) in {:.1f} s{}\n", a.out, r.bytes / 1e6, r.wall_seconds, kept);
  return 0;
}

}  // namespace sewer3d::cli
