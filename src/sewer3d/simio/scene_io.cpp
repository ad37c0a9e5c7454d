#include "sewer3d/simio/scene_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/simio/render_json.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;

const char* TypeName(Scene::Type t) {
  switch (t) {
    case Scene::Type::kPlane:
      return "plane";
    case Scene::Type::kCylinder:
      return "cylinder";
    case Scene::Type::kPipeWall:
      return "pipe_wall";
  }
  return "plane";
}
// A scene file's clock angle (deg from where the optical axis meets the wall) in the clock hours
// of PipeFeature (12 h = 360°), and back.
double ClockDegToHours(double clock_deg) { return clock_deg / 30.0; }
double ClockHoursToDeg(double clock_h) { return clock_h * 30.0; }

// One feature of a pipe-wall scene file, `prefix` "features[i].".
PipeFeature ParseSceneFeature(const JsonReader& in, const json& f, const std::string& prefix) {
  if (!f.is_object()) in.Fail(prefix, "must be an object");
  if (f.contains("clock_h")) {
    in.Fail(prefix + "clock_h",
            "is a scenario's clock; a scene places features by clock_deg (degrees from "
            "where the camera's optical axis meets the wall)");
  }
  in.OnlyKnown(f, prefix,
               {"type", "station_mm", "clock_deg", "gap_mm", "offset_mm", "radius_mm", "width_mm",
                "length_mm", "angle_deg", "height_mm", "depth_mm"});
  PipeFeature ft;
  const std::string kind = in.Text(f, "type", prefix, "");
  const auto type = PipeFeatureTypeFromName(kind);
  if (!type) in.Fail(prefix + "type", "must be joint, bump, pit, crack or wet, got '" + kind + "'");
  ft.type = *type;  // Scene::Check rejects the kinds only a pipe world takes
  ft.station_mm = in.Number(f, "station_mm", prefix, 0.0);
  // The file's angle, in the file's unit: Scene::Check's ±12 h would name clock_h.
  const double clock_deg = in.Number(f, "clock_deg", prefix, 0.0);
  if (!(std::abs(clock_deg) <= 360.0))
    in.Fail(prefix + "clock_deg", fmt::format("must be within ±360°, got {:g}", clock_deg));
  ft.clock_h = ClockDegToHours(clock_deg);
  ft.gap_mm = in.Number(f, "gap_mm", prefix, 0.0);
  ft.offset_mm = in.Number(f, "offset_mm", prefix, 0.0);
  ft.radius_mm = in.Number(f, "radius_mm", prefix, 0.0);
  ft.width_mm = in.Number(f, "width_mm", prefix, 0.0);
  ft.length_mm = in.Number(f, "length_mm", prefix, 0.0);
  ft.angle_deg = in.Number(f, "angle_deg", prefix, 0.0);
  // A bump's height rises out of the wall; pits, cracks and joint gaps have a depth into it,
  // which files before depth_mm gave as height_mm.
  if (ft.type == PipeFeature::Type::kBump)
    ft.height_mm = in.Number(f, "height_mm", prefix, 0.0);
  else
    ft.depth_mm = in.Number(f, "depth_mm", prefix, in.Number(f, "height_mm", prefix, 0.0));
  return ft;
}

}  // namespace

Scene ParseScene(const std::string& text, const std::filesystem::path& path) {
  const JsonReader in(path);
  const json j = in.ParseObject(text);
  Scene s;
  if (!j.contains("type")) {
    const std::string kind = KnownFileKind(j);
    in.Fail("type", "is missing: " + (kind.empty() ? "" : "this is " + kind + ", not a scene; ") +
                        "a scene file (or a rendered frame's scene.json) has type plane, "
                        "cylinder or pipe_wall");
  }
  // A flat scene file carries its render options, seed and module beside the geometry.
  in.OnlyKnown(j, "",
               {"type", "material", "material_seed", "distance_mm", "tilt_deg", "diameter_mm",
                "axis", "axis_point_mm", "features", "render", "seed", "module", "depth_range_mm"});
  const std::string type = in.Text(j, "type", "", "");
  if (type == "plane")
    s.type = Scene::Type::kPlane;
  else if (type == "cylinder")
    s.type = Scene::Type::kCylinder;
  else if (type == "pipe_wall")
    s.type = Scene::Type::kPipeWall;
  else
    in.Fail("type", "must be plane, cylinder or pipe_wall, got '" + type + "'");
  // The other kind's members are refused, not ignored (a plane turned into a cylinder by hand
  // would keep its distance_mm without effect).
  const bool plane = s.type == Scene::Type::kPlane;
  for (const char* key :
       plane ? std::vector<const char*>{"diameter_mm", "axis", "axis_point_mm", "features"}
             : std::vector<const char*>{"distance_mm", "tilt_deg"}) {
    if (j.contains(key)) {
      in.Fail(key, std::string("does not apply to a ") + type + " scene (only to " +
                       (plane ? "cylinder and pipe_wall" : "plane") + " scenes)");
    }
  }
  s.material = ParseMaterial(in, in.Text(j, "material", "", "concrete"), "material");
  s.material_seed = in.Seed(j, "material_seed", "", 1);
  s.distance_mm = in.Number(j, "distance_mm", "", s.distance_mm);
  s.tilt_deg = in.Number(j, "tilt_deg", "", s.tilt_deg);
  s.diameter_mm = in.Number(j, "diameter_mm", "", s.diameter_mm);
  s.axis = in.Vector(j, "axis", "", s.axis);
  s.axis_point_mm = in.Vector(j, "axis_point_mm", "", s.axis_point_mm);
  if (const auto it = j.find("features"); it != j.end()) {
    if (!it->is_array()) in.Fail("features", "must be an array");
    for (size_t i = 0; i < it->size(); ++i) {
      s.features.push_back(ParseSceneFeature(in, (*it)[i], "features[" + std::to_string(i) + "]."));
    }
  }
  ValidateFileContents(path, [&] { s.Check(); });
  return s;
}

Scene ReadScene(const std::filesystem::path& path) {
  const std::string text = ReadTextFile(path);
  try {
    const json doc = json::parse(text);
    if (doc.is_object() && doc.contains("scene")) {
      // A rendered frame's scene.json: the geometry under "scene", the rest beside it.
      const JsonReader in(path);
      if (!doc["scene"].is_object()) in.Fail("scene", "must be an object");
      in.OnlyKnown(doc, "", {"scene", "render", "seed", "module", "depth_range_mm"});
      for (const char* beside : {"render", "seed", "module", "depth_range_mm"}) {
        if (doc["scene"].contains(beside))
          in.Fail(std::string("scene.") + beside, "belongs beside \"scene\", not in it");
      }
      return ParseScene(doc["scene"].dump(), path);
    }
  } catch (const json::exception&) {
    // ParseScene reports it.
  }
  return ParseScene(text, path);
}

bool ReadSceneRenderOptions(const std::filesystem::path& path, RenderOptions& options) {
  const JsonReader in(path);
  const json doc = in.ParseObject(ReadTextFile(path));
  const auto render = doc.find("render");
  if (render == doc.end()) return false;
  if (!render->is_object()) in.Fail("render", "must be an object of render options");
  ReadRenderOptions(in, *render, "render.", options);
  options.seed = in.Seed(doc, "seed", "", options.seed);
  ValidateFileContents(path, [&] { CheckWithin("render.", [&] { options.Check(); }); });
  return true;
}

std::string ReadSceneModule(const std::filesystem::path& path) {
  const JsonReader in(path);
  const std::filesystem::path named = in.Text(in.ParseObject(ReadTextFile(path)), "module", "", "");
  if (named.empty() || named.is_absolute()) return named.string();
  // Relative to the scene file; files written before that named it from the folder they were
  // rendered in.
  const std::filesystem::path beside = path.parent_path() / named;
  std::error_code ec;
  return std::filesystem::exists(beside, ec) || !std::filesystem::exists(named, ec)
             ? beside.lexically_normal().string()
             : named.string();
}

std::string SceneToJson(const Scene& s) {
  json j;
  j["type"] = TypeName(s.type);
  j["material"] = MaterialName(s.material);
  j["material_seed"] = s.material_seed;
  if (s.type == Scene::Type::kPlane) {
    j["distance_mm"] = s.distance_mm;
    j["tilt_deg"] = s.tilt_deg;
  } else {
    j["diameter_mm"] = s.diameter_mm;
    j["axis"] = {s.axis.x(), s.axis.y(), s.axis.z()};
    j["axis_point_mm"] = {s.axis_point_mm.x(), s.axis_point_mm.y(), s.axis_point_mm.z()};
    j["features"] = json::array();
    for (const auto& f : s.features) {
      j["features"].push_back({{"type", PipeFeatureTypeName(f.type)},
                               {"station_mm", f.station_mm},
                               {"clock_deg", ClockHoursToDeg(f.clock_h)},
                               {"gap_mm", f.gap_mm},
                               {"offset_mm", f.offset_mm},
                               {"height_mm", f.height_mm},
                               {"depth_mm", f.depth_mm},
                               {"radius_mm", f.radius_mm},
                               {"width_mm", f.width_mm},
                               {"length_mm", f.length_mm},
                               {"angle_deg", f.angle_deg}});
    }
  }
  return j.dump(2);
}

void WritePatternImage(const std::filesystem::path& path, const RenderedFrame& frame, int bits) {
  cv::Mat pattern;
  if (bits == 8)
    frame.pattern.convertTo(pattern, CV_8U);
  else
    pattern = frame.pattern;
  WriteImage(path, pattern);
}

void WriteTextureImage(const std::filesystem::path& path, const RenderedFrame& frame, int bits) {
  if (!frame.texture_raw.empty()) {  // Bayer raw: 8 bits, or the full 16-bit range above 8
    cv::Mat raw;
    if (bits == 8)
      frame.texture_raw.convertTo(raw, CV_8U);
    else
      frame.texture_raw.convertTo(raw, CV_16U, 65535.0 / ((1 << bits) - 1));
    WriteImage(path, raw);
    return;
  }
  cv::Mat texture8, bgr;
  frame.texture.convertTo(texture8, CV_8U, 255.0 / ((1 << bits) - 1));
  cv::cvtColor(texture8, bgr, cv::COLOR_RGB2BGR);
  WriteImage(path, bgr);
}

void WriteRenderedFrame(const std::filesystem::path& dir, const RenderedFrame& frame,
                        const Scene& scene, const RenderOptions& o,
                        const std::filesystem::path& module_path) {
  CreateOutputFolder(dir);
  WritePatternImage(dir / "pattern.png", frame, o.sensor.bits);
  WriteTextureImage(dir / "texture.png", frame, o.sensor.bits);
  WriteImage(dir / "truth_depth.tiff", frame.truth_depth);
  const auto [lo, hi] = WriteDepthPreview(dir / "depth_preview.png", frame.truth_depth);

  json doc;
  doc["scene"] = json::parse(SceneToJson(scene));
  doc["seed"] = o.seed;
  // Relative to the scene file, as a scenario's module is: the folder can move with its module.
  std::error_code ec;
  const std::filesystem::path relative = std::filesystem::relative(module_path, dir, ec);
  doc["module"] =
      (ec || relative.empty() ? std::filesystem::absolute(module_path) : relative).generic_string();
  doc["render"] = RenderOptionsToJson(o);
  doc["depth_range_mm"] = {lo, hi};
  WriteTextFile(dir / "scene.json", doc.dump(2) + "\n");
}

}  // namespace sewer3d

namespace sewer3d {

const char* MaterialName(Material m) {
  switch (m) {
    case Material::kConcrete:
      return "concrete";
    case Material::kVitrifiedClay:
      return "vitrified_clay";
    case Material::kPlastic:
      return "plastic";
    case Material::kSediment:
      return "sediment";
    case Material::kPolyethylene:
      return "polyethylene";
  }
  return "concrete";
}

Material ParseMaterial(const JsonReader& in, const std::string& name, const std::string& field) {
  for (const Material m : {Material::kConcrete, Material::kVitrifiedClay, Material::kPlastic,
                           Material::kSediment, Material::kPolyethylene}) {
    if (name == MaterialName(m)) return m;
  }
  in.Fail(field, "must be concrete, vitrified_clay, plastic, polyethylene or sediment, got '" +
                     name + "'");
}

namespace {

// An f-number in a file: null is a pinhole (no defocus; held as 0), a number is a lens's
// f-number. 0 is refused: it would read as an aperture without limit, not as a pinhole.
nlohmann::json FNumberJson(double f_number) {
  return f_number > 0.0 ? nlohmann::json(f_number) : nlohmann::json(nullptr);
}

double ReadFNumber(const JsonReader& in, const nlohmann::json& j, const char* key,
                   const std::string& p, double fallback) {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  if (it->is_null()) return 0.0;
  const double f_number = in.Number(j, key, p);
  if (!(f_number >= 0.5 && f_number <= 64.0))
    in.Fail(p + key, fmt::format("must be an f-number from 0.5 to 64 (null: a pinhole, no "
                                 "defocus), got {:g}",
                                 f_number));
  return f_number;
}

}  // namespace

nlohmann::json RenderOptionsToJson(const RenderOptions& o) {
  return {{"supersampling", o.supersampling},
          {"sensor_width_mm", o.sensor_width_mm},
          {"camera_f_number", FNumberJson(o.camera_f_number)},
          {"camera_focus_mm", o.camera_focus_mm},
          {"projector_f_number", FNumberJson(o.projector_f_number)},
          {"projector_focus_mm", o.projector_focus_mm},
          {"projector_psf_px", o.projector_psf_px},
          {"texture_level", o.texture_level},
          {"pattern_level", o.pattern_level},
          {"ambient_level", o.ambient_level},
          {"vignetting", o.vignetting},
          {"ring_light_exponent", o.ring_light_exponent},
          {"ring_light_color_shift", o.ring_light_color_shift},
          {"color_shading", {o.color_shading.x(), o.color_shading.y(), o.color_shading.z()}},
          {"white_balance", {o.white_balance.x(), o.white_balance.y(), o.white_balance.z()}},
          {"truth_albedo", o.truth_albedo},
          {"speed_mm_s", o.speed_mm_s},
          {"exposure_ms", o.exposure_ms},
          {"motion_direction",
           {o.motion_direction.x(), o.motion_direction.y(), o.motion_direction.z()}},
          {"full_well_e", o.sensor.full_well_e},
          {"read_noise_e", o.sensor.read_noise_e},
          {"bits", o.sensor.bits},
          {"noise", o.sensor.noise},
          {"color_filter", ColorFilterName(o.sensor.color_filter)},
          {"wet_film_roughness", o.wet_film.roughness},
          {"wet_film_refractive_index", o.wet_film.refractive_index},
          {"wet_film_darkening", o.wet_film.darkening},
          {"spot_placement_sigma_px", o.spot_errors.placement_sigma_px},
          {"spot_gain_sigma", o.spot_errors.gain_sigma},
          {"speckle_contrast", o.spot_errors.speckle_contrast},
          {"speckle_wavelength_nm", o.spot_errors.wavelength_nm},
          {"lens_residual", o.spot_errors.lens_residual},
          {"relief_mm", o.spot_errors.relief_mm},
          {"relief_plastic_mm", o.spot_errors.relief_plastic_mm},
          {"relief_scale_mm", o.spot_errors.relief_scale_mm},
          {"subsurface_mm", o.spot_errors.subsurface_mm},
          {"subsurface_plastic_mm", o.spot_errors.subsurface_plastic_mm},
          {"calibration_focal_px", o.spot_errors.calibration_focal_px},
          {"calibration_centre_px", o.spot_errors.calibration_centre_px},
          {"calibration_baseline_mm", o.spot_errors.calibration_baseline_mm},
          {"calibration_rotation_deg", o.spot_errors.calibration_rotation_deg},
          {"projector_seed", o.spot_errors.projector_seed},
          {"reference_width_px", o.spot_errors.reference_width_px}};
}

namespace {

// The members a realism profile sets.
constexpr const char* kProfileMembers[] = {"spot_placement_sigma_px",
                                           "spot_gain_sigma",
                                           "speckle_contrast",
                                           "lens_residual",
                                           "relief_mm",
                                           "relief_plastic_mm",
                                           "subsurface_mm",
                                           "subsurface_plastic_mm",
                                           "calibration_focal_px",
                                           "calibration_centre_px",
                                           "calibration_baseline_mm",
                                           "calibration_rotation_deg"};

}  // namespace

void ReadRenderOptions(const JsonReader& in, const nlohmann::json& j, const std::string& p,
                       RenderOptions& o) {
  in.OnlyKnown(j, p,
               {"supersampling",
                "sensor_width_mm",
                "camera_f_number",
                "camera_focus_mm",
                "projector_f_number",
                "projector_focus_mm",
                "projector_psf_px",
                "texture_level",
                "pattern_level",
                "ambient_level",
                "vignetting",
                "ring_light_exponent",
                "ring_light_color_shift",
                "color_shading",
                "white_balance",
                "truth_albedo",
                "speed_mm_s",
                "exposure_ms",
                "motion_direction",
                "full_well_e",
                "read_noise_e",
                "bits",
                "noise",
                "color_filter",
                "wet_film_roughness",
                "wet_film_refractive_index",
                "wet_film_darkening",
                "realism",
                "spot_placement_sigma_px",
                "spot_gain_sigma",
                "speckle_contrast",
                "speckle_wavelength_nm",
                "lens_residual",
                "relief_mm",
                "relief_plastic_mm",
                "relief_scale_mm",
                "subsurface_mm",
                "subsurface_plastic_mm",
                "calibration_focal_px",
                "calibration_centre_px",
                "calibration_baseline_mm",
                "calibration_rotation_deg",
                "projector_seed",
                "reference_width_px"});
  o.supersampling = in.Integer(j, "supersampling", p, o.supersampling);
  o.sensor_width_mm = in.Number(j, "sensor_width_mm", p, o.sensor_width_mm);
  o.camera_f_number = ReadFNumber(in, j, "camera_f_number", p, o.camera_f_number);
  o.camera_focus_mm = in.Number(j, "camera_focus_mm", p, o.camera_focus_mm);
  o.projector_f_number = ReadFNumber(in, j, "projector_f_number", p, o.projector_f_number);
  o.projector_focus_mm = in.Number(j, "projector_focus_mm", p, o.projector_focus_mm);
  o.projector_psf_px = in.Number(j, "projector_psf_px", p, o.projector_psf_px);
  o.texture_level = in.Number(j, "texture_level", p, o.texture_level);
  o.pattern_level = in.Number(j, "pattern_level", p, o.pattern_level);
  o.ambient_level = in.Number(j, "ambient_level", p, o.ambient_level);
  o.vignetting = in.Bool(j, "vignetting", p, o.vignetting);
  o.ring_light_exponent = in.Number(j, "ring_light_exponent", p, o.ring_light_exponent);
  o.ring_light_color_shift = in.Number(j, "ring_light_color_shift", p, o.ring_light_color_shift);
  o.color_shading = in.Vector(j, "color_shading", p, o.color_shading);
  o.white_balance = in.Vector(j, "white_balance", p, o.white_balance);
  o.truth_albedo = in.Bool(j, "truth_albedo", p, o.truth_albedo);
  o.speed_mm_s = in.Number(j, "speed_mm_s", p, o.speed_mm_s);
  o.exposure_ms = in.Number(j, "exposure_ms", p, o.exposure_ms);
  o.motion_direction = in.Vector(j, "motion_direction", p, o.motion_direction);
  o.sensor.full_well_e = in.Number(j, "full_well_e", p, o.sensor.full_well_e);
  o.sensor.read_noise_e = in.Number(j, "read_noise_e", p, o.sensor.read_noise_e);
  o.sensor.bits = in.Integer(j, "bits", p, o.sensor.bits);
  o.sensor.noise = in.Bool(j, "noise", p, o.sensor.noise);
  const std::string filter = in.Text(j, "color_filter", p, ColorFilterName(o.sensor.color_filter));
  const auto parsed = ParseColorFilter(filter);
  if (!parsed) in.Fail(p + "color_filter", "must be none or RGGB, got '" + filter + "'");
  o.sensor.color_filter = *parsed;
  WetFilmOptions& film = o.wet_film;
  film.roughness = in.Number(j, "wet_film_roughness", p, film.roughness);
  film.refractive_index = in.Number(j, "wet_film_refractive_index", p, film.refractive_index);
  film.darkening = in.Number(j, "wet_film_darkening", p, film.darkening);
  // A realism profile first, then any of its values given beside it (in any order) over it.
  if (j.contains("realism")) {
    const std::string name = in.Text(j, "realism", p, "ideal");
    const auto profile = RealismProfile(name);
    if (!profile) in.Fail(p + "realism", "must be ideal or paper, got '" + name + "'");
    const auto given = [&](const char* key) { return j.contains(key); };
    if (std::all_of(std::begin(kProfileMembers), std::end(kProfileMembers), given)) {
      in.Fail(p + "realism",
              "has no effect: every error source '" + name +
                  "' sets is also given beside it "
                  "(a written scene or scenario lists them all); remove those members, or realism");
    }
    o.spot_errors = *profile;
  }
  SpotErrors& e = o.spot_errors;
  e.placement_sigma_px = in.Number(j, "spot_placement_sigma_px", p, e.placement_sigma_px);
  e.gain_sigma = in.Number(j, "spot_gain_sigma", p, e.gain_sigma);
  e.speckle_contrast = in.Number(j, "speckle_contrast", p, e.speckle_contrast);
  e.wavelength_nm = in.Number(j, "speckle_wavelength_nm", p, e.wavelength_nm);
  e.lens_residual = in.Number(j, "lens_residual", p, e.lens_residual);
  e.relief_mm = in.Number(j, "relief_mm", p, e.relief_mm);
  e.relief_plastic_mm = in.Number(j, "relief_plastic_mm", p, e.relief_plastic_mm);
  e.relief_scale_mm = in.Number(j, "relief_scale_mm", p, e.relief_scale_mm);
  e.subsurface_mm = in.Number(j, "subsurface_mm", p, e.subsurface_mm);
  e.subsurface_plastic_mm = in.Number(j, "subsurface_plastic_mm", p, e.subsurface_plastic_mm);
  e.calibration_focal_px = in.Number(j, "calibration_focal_px", p, e.calibration_focal_px);
  e.calibration_centre_px = in.Number(j, "calibration_centre_px", p, e.calibration_centre_px);
  e.calibration_baseline_mm = in.Number(j, "calibration_baseline_mm", p, e.calibration_baseline_mm);
  e.calibration_rotation_deg =
      in.Number(j, "calibration_rotation_deg", p, e.calibration_rotation_deg);
  e.projector_seed = in.Seed(j, "projector_seed", p, e.projector_seed);
  e.reference_width_px = in.Integer(j, "reference_width_px", p, e.reference_width_px);
}

}  // namespace sewer3d
