// `sewer3d simulate frame`'s scene from its options: plane, cylinder or pipe-wall from the
// geometry flags, or a scene JSON file (cmd_simulate.cpp renders it).

#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <vector>

#include "sewer3d/cli/flag_names.hpp"
#include "sewer3d/cli/simulate_commands.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/sim/scene_presets.hpp"
#include "sewer3d/simio/scene_io.hpp"

namespace sewer3d::cli {
namespace {

// Checks a scene built from the options, naming the option where the scene names its field.
void CheckSceneOptions(const Scene& scene) {
  try {
    scene.Check();
  } catch (const InvalidValue& e) {
    if (e.field().rfind("features[", 0) == 0) {  // the built-in pipe-wall features
      throw InvalidValue("--diameter-mm",
                         "the pipe-wall preset's joint, bump, pit and crack do not fit this "
                         "diameter (" +
                             e.field() + ": " + e.problem() + ")");
    }
    throw WithFlagNames(e, {{"distance_mm", "--distance-mm"},
                            {"tilt_deg", "--tilt-deg"},
                            {"diameter_mm", "--diameter-mm"},
                            {"axis_point_mm", "--decentre-mm"},
                            {"axis", "--axis"}});
  }
}

bool IsBuiltInScene(const std::string& name) {
  return name == "plane" || name == "cylinder" || name == "pipe-wall";
}

// The geometry flags of the other kind of built-in scene are refused, not ignored.
void CheckSceneFlags(const std::string& scene, const CLI::App& frame) {
  const bool plane = scene == "plane";
  const auto flags = plane ? std::vector<const char*>{"--diameter-mm", "--decentre-mm", "--axis"}
                           : std::vector<const char*>{"--distance-mm", "--tilt-deg"};
  for (const char* flag : flags) {
    if (frame.count(flag) > 0) {
      throw InvalidValue(flag, std::string("does not apply to --scene ") + scene + " (only to " +
                                   (plane ? "cylinder and pipe-wall" : "plane") + ")");
    }
  }
}

// plane, cylinder or pipe-wall, from the options.
Scene BuiltInScene(const FrameArgs& a, const CLI::App& frame) {
  CheckSceneFlags(a.scene, frame);
  Scene scene;
  scene.type = a.scene == "plane"      ? Scene::Type::kPlane
               : a.scene == "cylinder" ? Scene::Type::kCylinder
                                       : Scene::Type::kPipeWall;
  scene.material = a.material == "plastic"          ? Material::kPlastic
                   : a.material == "polyethylene"   ? Material::kPolyethylene
                   : a.material == "vitrified_clay" ? Material::kVitrifiedClay
                                                    : Material::kConcrete;
  scene.distance_mm = a.distance;
  scene.tilt_deg = a.tilt;
  scene.diameter_mm = a.diameter;
  scene.axis_point_mm = {a.decentre[0], 0.0, a.decentre[1]};
  scene.axis = {a.axis[0], a.axis[1], a.axis[2]};
  if (scene.type == Scene::Type::kPipeWall) scene.features = PipeWallPresetFeatures();
  CheckSceneOptions(scene);
  return scene;
}

bool SameText(const std::filesystem::path& a, const std::filesystem::path& b) {
  try {
    return ReadTextFile(a) == ReadTextFile(b);
  } catch (const FileError&) {
    return false;  // one is no readable text file: not the module given
  }
}

// A rendered frame's scene.json names the module it was rendered with; this frame is rendered
// with --module, which the user is told where the two differ.
void WarnOfOtherModule(const std::filesystem::path& scene_file, const std::string& module) {
  const std::string named = ReadSceneModule(scene_file);
  if (named.empty()) return;
  std::error_code ec;
  if (!std::filesystem::exists(named, ec)) {
    fmt::print(stderr,
               "sewer3d: warning: {}: names the module {}, which is not there; rendering with "
               "--module {}\n",
               scene_file.string(), named, module);
  } else if (!std::filesystem::equivalent(named, module, ec) && !SameText(named, module)) {
    fmt::print(stderr,
               "sewer3d: warning: {}: was rendered with the module {}; rendering with --module {} "
               "instead\n",
               scene_file.string(), named, module);
  }
}

// A scene file; its render options, with the render flags given on the command line over them.
Scene FileScene(const FrameArgs& a, const CLI::App& frame, RenderOptions& options) {
  const std::filesystem::path file(a.scene);
  if (file.extension() != ".json" && !std::filesystem::exists(file)) {
    throw InvalidValue("--scene",
                       "must be plane, cylinder, pipe-wall or a scene JSON file, got " + a.scene);
  }
  // The geometry flags describe the built-in scenes; a scene file has its own.
  for (const char* flag :
       {"--material", "--distance-mm", "--tilt-deg", "--diameter-mm", "--decentre-mm", "--axis"}) {
    if (frame.count(flag) > 0) {
      throw InvalidValue(flag, "applies to the built-in scenes; " + a.scene +
                                   " sets its own (edit the file instead)");
    }
  }
  Scene scene = ReadScene(file);
  if (ReadSceneRenderOptions(file, options)) {
    if (frame.count("--seed")) options.seed = a.render.seed;
    if (frame.count("--supersampling")) options.supersampling = a.render.supersampling;
    if (frame.count("--bits")) options.sensor.bits = a.render.sensor.bits;
    if (frame.count("--speed-mm-s")) options.speed_mm_s = a.render.speed_mm_s;
    if (frame.count("--exposure-ms")) options.exposure_ms = a.render.exposure_ms;
    if (frame.count("--realism")) options.spot_errors = *RealismProfile(a.realism);
  }
  WarnOfOtherModule(file, a.module);  // once the file is known good: an error is one line
  return scene;
}

}  // namespace

Scene FrameScene(const FrameArgs& a, const CLI::App& frame, RenderOptions& options) {
  return IsBuiltInScene(a.scene) ? BuiltInScene(a, frame) : FileScene(a, frame, options);
}

}  // namespace sewer3d::cli
