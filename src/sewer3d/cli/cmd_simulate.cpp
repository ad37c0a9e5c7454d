// `sewer3d simulate frame`: renders one module's pattern and texture images of a scene.

#include <fmt/core.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <sstream>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/progress_bar.hpp"
#include "sewer3d/cli/simulate_commands.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/simio/scenario_io.hpp"
#include "sewer3d/simio/scene_io.hpp"
#include "sewer3d/simio/simulate_run.hpp"

namespace sewer3d::cli {
namespace {

// The pipe-wall preset: a DN300 wall with a displaced open joint, an intrusion, a pit and a
// crack, all inside the default module's field of view.
std::vector<PipeFeature> PipeWallPreset() {
  using T = PipeFeature::Type;
  // Clock positions in hours, 12 h = 360° (so −18° is −18 / 30 h) from the view direction.
  return {{.type = T::kJointStep,
           .station_mm = 45.0,
           .clock_h = 0.0,
           .depth_mm = 4.0,
           .gap_mm = 6.0,
           .offset_mm = 5.0},
          {.type = T::kBump,
           .station_mm = 10.0,
           .clock_h = -18.0 / 30.0,
           .height_mm = 6.0,
           .radius_mm = 6.0},
          {.type = T::kPit,
           .station_mm = 0.0,
           .clock_h = 15.0 / 30.0,
           .depth_mm = 4.0,
           .radius_mm = 10.0},
          {.type = T::kCrack,
           .station_mm = 90.0,
           .clock_h = -5.0 / 30.0,
           .length_mm = 60.0,
           .width_mm = 1.0,
           .depth_mm = 2.0,
           .angle_deg = 70.0}};
}

// Checks a scene built from the options, naming the option where the scene names its field.
void CheckSceneOptions(const Scene& scene) {
  try {
    scene.Check();
  } catch (const InvalidValue& e) {
    static const std::map<std::string, std::string> kOption{{"distance_mm", "--distance-mm"},
                                                            {"tilt_deg", "--tilt-deg"},
                                                            {"diameter_mm", "--diameter-mm"},
                                                            {"axis_point_mm", "--decentre-mm"},
                                                            {"axis", "--axis"}};
    const auto it = kOption.find(e.field());
    if (it == kOption.end()) throw;
    throw InvalidValue(it->second, e.problem());
  }
}

void AddRunCommand(CLI::App& sim, RunArgs& a) {
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
  run->add_flag("--quiet", a.quiet, "No progress bar");
  run->add_flag("--allow-large", a.allow_large,
                "Run even when the plan exceeds 200 000 images, 20 M odometry rows or the free "
                "disk space");
}

}  // namespace

int RunRun(const RunArgs& a) {
  if (a.scenario.empty() && a.preset.empty()) {
    std::fprintf(stderr, "sewer3d: error: simulate run needs --scenario FILE or --preset NAME\n");
    return 2;
  }
  Scenario s = a.scenario.empty() ? PresetScenario(a.preset) : ReadScenario(a.scenario);
  if (a.seed != 0) s.seed = a.seed;
  if (a.supersampling != 0) s.render.supersampling = a.supersampling;
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
  auto simulate = [&] { r = SimulateRun(s, module, pattern, a.out, progress); };
  const auto in_scenario = [&](const auto& step) {
    if (a.scenario.empty())
      step();
    else
      ValidateFileContents(a.scenario, step);
  };
  in_scenario(estimate);
  if (!a.allow_large) {
    try {
      CheckRunFits(size, a.out);
    } catch (const InvalidValue& e) {
      throw InvalidValue("", e.problem() + " (--allow-large runs it anyway)");
    }
  }
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
  fmt::print("wrote {} ({:.1f} MB) in {:.1f} s\n", a.out, r.bytes / 1e6, r.wall_seconds);
  return 0;
}

Command AddSimulateCommand(CLI::App& app) {
  struct Args {
    std::string module, scene = "plane", out, material = "concrete";
    double distance = 140.0, tilt = 0.0, diameter = 300.0;
    std::vector<double> decentre{0.0, 0.0};
    std::vector<double> axis{0.0, 1.0, 0.0};
    bool ideal = false;
    RenderOptions render;
  };
  auto args = std::make_shared<Args>();
  auto run_args = std::make_shared<RunArgs>();
  auto calibration_args = std::make_shared<CalibrationArgs>();
  CLI::App* sim = app.add_subcommand("simulate", "Render simulated captures");
  sim->require_subcommand(1);
  CLI::App* frame =
      sim->add_subcommand("frame", "Render one module's pattern and texture images of a scene");
  frame->add_option("--module", args->module, "module.json")->required()->check(CLI::ExistingFile);
  frame->add_option("--scene", args->scene, "plane, cylinder, pipe-wall, or a scene JSON file")
      ->capture_default_str();
  frame->add_option("--out", args->out, "Output folder")->required();
  frame->add_option("--seed", args->render.seed, "Noise / sampling seed")
      ->capture_default_str()
      ->check(Digits());
  frame->add_option("--material", args->material, "concrete, vitrified_clay or plastic")
      ->capture_default_str()
      ->check(CLI::IsMember({"concrete", "vitrified_clay", "plastic"}));
  frame->add_option("--distance-mm", args->distance, "plane: distance along the optical axis")
      ->capture_default_str()
      ->check(CLI::Range(10.0, 5000.0));
  frame->add_option("--tilt-deg", args->tilt, "plane: tilt about the camera x axis")
      ->capture_default_str()
      ->check(CLI::Range(-80.0, 80.0));
  frame->add_option("--diameter-mm", args->diameter, "cylinder / pipe-wall: inner diameter")
      ->capture_default_str()
      ->check(CLI::Range(20.0, 5000.0));
  frame
      ->add_option("--decentre-mm", args->decentre,
                   "cylinder / pipe-wall: axis offset (x z) from the camera")
      ->expected(2);
  frame
      ->add_option("--axis", args->axis,
                   "cylinder / pipe-wall: axis direction (x y z, camera frame)")
      ->expected(3);
  frame->add_option("--supersampling", args->render.supersampling, "S x S samples per pixel")
      ->capture_default_str()
      ->check(CLI::Range(1, 16));
  frame->add_option("--bits", args->render.sensor.bits, "ADC bits (8..12)")
      ->capture_default_str()
      ->check(CLI::Range(8, 12));
  frame
      ->add_option("--speed-mm-s", args->render.speed_mm_s,
                   "Rig speed along the carrier axis (motion blur)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10000.0));
  frame->add_option("--exposure-ms", args->render.exposure_ms, "Exposure time")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1000.0));
  frame->add_flag("--ideal", args->ideal, "No noise, defocus, ambient light or vignetting");
  AddRunCommand(*sim, *run_args);
  AddCalibrationCommand(*sim, *calibration_args);
  return {
      sim, [args, run_args, calibration_args, frame] {
        if (calibration_args->app->parsed()) return RunCalibration(*calibration_args);
        if (!frame->parsed()) return RunRun(*run_args);
        const LoadedModule loaded = LoadModule(args->module);
        Scene scene;
        if (args->scene == "plane" || args->scene == "cylinder" || args->scene == "pipe-wall") {
          scene.type = args->scene == "plane"      ? Scene::Type::kPlane
                       : args->scene == "cylinder" ? Scene::Type::kCylinder
                                                   : Scene::Type::kPipeWall;
          scene.material = args->material == "plastic"          ? Material::kPlastic
                           : args->material == "vitrified_clay" ? Material::kVitrifiedClay
                                                                : Material::kConcrete;
          scene.distance_mm = args->distance;
          scene.tilt_deg = args->tilt;
          scene.diameter_mm = args->diameter;
          scene.axis_point_mm = {args->decentre[0], 0.0, args->decentre[1]};
          scene.axis = {args->axis[0], args->axis[1], args->axis[2]};
          if (scene.type == Scene::Type::kPipeWall) scene.features = PipeWallPreset();
          CheckSceneOptions(scene);
        } else {
          scene = ReadScene(args->scene);
        }
        RenderOptions options = args->render;
        if (args->ideal) {
          const RenderOptions ideal = RenderOptions::Ideal();
          options.camera_f_number = ideal.camera_f_number;
          options.projector_f_number = ideal.projector_f_number;
          options.ambient_level = ideal.ambient_level;
          options.vignetting = ideal.vignetting;
          options.sensor.noise = false;
        }
        const auto start = std::chrono::steady_clock::now();
        const RenderedFrame rendered = RenderFrame(loaded.module, loaded.pattern, scene, options);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        WriteRenderedFrame(args->out, rendered, scene, options, args->module);
        fmt::print("rendered {}x{} px, {} samples in {:.2f} s ({:.1f} M samples/s)\n",
                   loaded.module.camera.width, loaded.module.camera.height, rendered.samples,
                   seconds, rendered.samples / seconds * 1e-6);
        fmt::print(
            "wrote {}/pattern.png, texture.png, truth_depth.tiff, depth_preview.png, scene.json\n",
            args->out);
        return 0;
      }};
}

}  // namespace sewer3d::cli
