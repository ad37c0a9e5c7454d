#include "sewer3d/io/module_io.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;

CameraIntrinsics ReadIntrinsics(const JsonReader& in, const json& root, const char* name) {
  const json& j = in.RequiredObject(root, name, "");
  const std::string p = std::string(name) + ".";
  in.NoNearMisses(j, p, {"width", "height", "fx", "fy", "cx", "cy", "k"});
  CameraIntrinsics c;
  c.width = in.PositiveSize(j, "width", p);
  c.height = in.PositiveSize(j, "height", p);
  c.fx = in.Positive(j, "fx", p);
  c.fy = in.Positive(j, "fy", p);
  c.cx = in.Number(j, "cx", p);
  c.cy = in.Number(j, "cy", p);
  const auto k = in.Numbers(j, "k", p, 3);
  c.k = {k[0], k[1], k[2]};
  return c;
}

json ObjectOr(const json& doc, const char* key) {
  const auto it = doc.find(key);
  return it != doc.end() && it->is_object() ? *it : json::object();
}

}  // namespace

ModuleDescription ParseModule(const std::string& text, const std::filesystem::path& path) {
  const JsonReader in(path);
  const json root = in.ParseObject(text);
  if (!root.contains("camera")) {
    if (const std::string kind = KnownFileKind(root); !kind.empty() && kind != "a module file")
      in.Fail("camera", "is missing: this is " + kind + ", not a module file");
  }
  in.NoNearMisses(root, "", {"camera", "projector", "projector_from_camera", "pattern"});
  ModuleDescription m;
  m.camera = ReadIntrinsics(in, root, "camera");
  m.projector = ReadIntrinsics(in, root, "projector");
  m.projector_from_camera = in.Pose(root, "projector_from_camera", "");
  const json& pattern = in.RequiredObject(root, "pattern", "");
  in.NoNearMisses(pattern, "pattern.", {"matrix", "pitch_px", "spot_diameter_px", "offset_px"});
  m.pattern.matrix_path = in.Text(pattern, "matrix", "pattern.");
  m.pattern.pitch_px = in.Positive(pattern, "pitch_px", "pattern.");
  m.pattern.spot_diameter_px = in.Positive(pattern, "spot_diameter_px", "pattern.");
  if (m.pattern.spot_diameter_px > m.pattern.pitch_px) {
    in.Fail("pattern.spot_diameter_px", "must not exceed pattern.pitch_px");
  }
  const auto offset = in.Numbers(pattern, "offset_px", "pattern.", 2);
  m.pattern.offset_px = {offset[0], offset[1]};
  m.source_json = text;
  ValidateFileContents(path, [&] { m.Check(); });
  return m;
}

namespace {

// A relative matrix path is looked up beside the module file as named ("./pattern.png" for a
// file in the working folder, so that the message shows where); for a symbolic link, beside the
// file it points to when the matrix is not beside the link.
std::filesystem::path MatrixBeside(const std::filesystem::path& module,
                                   const std::filesystem::path& matrix) {
  const std::filesystem::path folder =
      module.parent_path().empty() ? std::filesystem::path(".") : module.parent_path();
  std::error_code ec;
  if (std::filesystem::exists(folder / matrix, ec) || !std::filesystem::is_symlink(module, ec))
    return folder / matrix;
  const std::filesystem::path target = std::filesystem::canonical(module, ec);
  if (!ec && std::filesystem::exists(target.parent_path() / matrix, ec))
    return target.parent_path() / matrix;
  return folder / matrix;
}

}  // namespace

LoadedModule LoadModule(const std::filesystem::path& path) {
  LoadedModule loaded;
  loaded.module = ParseModule(ReadTextFile(path), path);
  std::filesystem::path matrix = loaded.module.pattern.matrix_path;
  if (matrix.is_relative()) matrix = MatrixBeside(path, matrix);
  try {
    loaded.pattern = ReadPatternMatrix(matrix);
  } catch (const FileError& e) {
    throw FileError(path,
                    "field 'pattern.matrix' names an unusable file: " + std::string(e.what()));
  }
  loaded.pattern_file = matrix;
  return loaded;
}

std::string ModuleToJson(const ModuleDescription& m) {
  json doc = json::object();
  if (!m.source_json.empty()) {
    try {
      doc = json::parse(m.source_json);
    } catch (const json::parse_error&) {
      doc = json::object();
    }
    if (!doc.is_object()) doc = json::object();
  }
  doc["camera"] = IntrinsicsJson(m.camera, ObjectOr(doc, "camera"));
  doc["projector"] = IntrinsicsJson(m.projector, ObjectOr(doc, "projector"));
  doc["projector_from_camera"] =
      PoseToJson(m.projector_from_camera, ObjectOr(doc, "projector_from_camera"));
  json pattern = ObjectOr(doc, "pattern");
  pattern["matrix"] = m.pattern.matrix_path;
  pattern["pitch_px"] = m.pattern.pitch_px;
  pattern["spot_diameter_px"] = m.pattern.spot_diameter_px;
  pattern["offset_px"] = {m.pattern.offset_px.x(), m.pattern.offset_px.y()};
  doc["pattern"] = pattern;
  return doc.dump(2) + "\n";
}

void SaveModule(const std::filesystem::path& path, const ModuleDescription& module) {
  module.Check();
  WriteTextFile(path, ModuleToJson(module));
}

}  // namespace sewer3d
