// `sewer3d simulate frame`: renders one module's pattern and texture images of a scene (built
// from the options in cmd_simulate_scene.cpp; `simulate run` and `simulate calibration` live
// in their own files).

#include <fmt/core.h>

#include <chrono>
#include <filesystem>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/simulate_commands.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/simio/scene_io.hpp"

namespace sewer3d::cli {
namespace {

// The frame's files must not replace a module's: its pattern.png is the pattern matrix.
void CheckFrameFolder(const std::filesystem::path& out, const LoadedModule& loaded) {
  std::error_code ec;
  const auto matrix = std::filesystem::weakly_canonical(loaded.pattern_file, ec);
  const auto image = std::filesystem::weakly_canonical(out / "pattern.png", ec);
  if (std::filesystem::exists(out / "run.json")) {
    throw InvalidValue("--out", out.string() +
                                    " holds a capture run, whose pattern.png the rendered image "
                                    "would replace; choose another folder");
  }
  if (std::filesystem::exists(out / "module.json") || (!ec && matrix == image)) {
    throw InvalidValue("--out", out.string() +
                                    " holds a module, whose pattern.png the rendered "
                                    "image would replace; choose another folder");
  }
  CheckNotInRunOrWorkspace(out, "--out");
}

int RunFrame(const FrameArgs& a, const CLI::App& frame) {
  const LoadedModule loaded = LoadModule(a.module);
  CheckFrameFolder(a.out, loaded);
  RenderOptions options = a.render;
  options.spot_errors = *RealismProfile(a.realism);
  const Scene scene = FrameScene(a, frame, options);
  if (a.ideal) {
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
  WriteRenderedFrame(a.out, rendered, scene, options, a.module);
  fmt::print("rendered {}x{} px, {} samples in {:.2f} s ({:.1f} M samples/s)\n",
             loaded.module.camera.width, loaded.module.camera.height, rendered.samples, seconds,
             rendered.samples / seconds * 1e-6);
  fmt::print("wrote {}/pattern.png, texture.png, truth_depth.tiff, depth_preview.png, scene.json\n",
             a.out);
  return 0;
}

}  // namespace

Command AddSimulateCommand(CLI::App& app) {
  auto args = std::make_shared<FrameArgs>();
  auto run_args = std::make_shared<RunArgs>();
  auto calibration_args = std::make_shared<CalibrationArgs>();
  auto inclinometer_args = std::make_shared<InclinometerArgs>();
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
  frame
      ->add_option("--material", args->material,
                   "concrete, vitrified_clay, plastic or polyethylene (black PE)")
      ->capture_default_str()
      ->check(CLI::IsMember({"concrete", "vitrified_clay", "plastic", "polyethylene"}));
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
  frame
      ->add_option("--realism", args->realism,
                   "Error sources of a real module and wall: ideal (none) or paper (spot "
                   "placement and power, speckle, lens residual, wall relief, subsurface "
                   "scattering, calibration error: the paper's accuracy)")
      ->capture_default_str()
      ->check(CLI::IsMember({"ideal", "paper"}));
  AddRunCommand(*sim, *run_args);
  AddCalibrationCommand(*sim, *calibration_args);
  AddInclinometerCommand(*sim, *inclinometer_args);
  return {sim, [args, run_args, calibration_args, inclinometer_args, frame] {
            if (calibration_args->app->parsed()) return RunCalibration(*calibration_args);
            if (inclinometer_args->app->parsed()) return RunInclinometer(*inclinometer_args);
            if (!frame->parsed()) return RunRun(*run_args);
            return RunFrame(*args, *frame);
          }};
}

}  // namespace sewer3d::cli
