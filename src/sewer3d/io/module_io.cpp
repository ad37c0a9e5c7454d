#include "sewer3d/io/module_io.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/json_reader.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;

/// Reads typed fields out of a JSON document, naming the file and the dotted field on error.
class FieldReader {
 public:
  explicit FieldReader(std::filesystem::path file) : file_(std::move(file)) {}

  [[noreturn]] void Fail(const std::string& field, const std::string& problem) const {
    throw FileError(file_, "field '" + field + "' " + problem);
  }

  const json& Object(const json& parent, const std::string& key, const std::string& prefix) const {
    const std::string field = prefix.empty() ? key : prefix + "." + key;
    const json& value = Member(parent, key, field);
    if (!value.is_object()) Fail(field, "must be an object");
    return value;
  }

  double Number(const json& parent, const std::string& key, const std::string& prefix) const {
    const std::string field = prefix + "." + key;
    const json& value = Member(parent, key, field);
    if (!value.is_number()) Fail(field, "must be a number, got " + value.dump());
    const double x = value.get<double>();
    if (!std::isfinite(x)) Fail(field, "must be finite");
    return x;
  }

  double Positive(const json& parent, const std::string& key, const std::string& prefix) const {
    const double x = Number(parent, key, prefix);
    if (!(x > 0.0)) Fail(prefix + "." + key, "must be positive, got " + Format(x));
    return x;
  }

  int PositiveInt(const json& parent, const std::string& key, const std::string& prefix) const {
    const std::string field = prefix + "." + key;
    const json& value = Member(parent, key, field);
    if (!value.is_number_integer()) Fail(field, "must be an integer, got " + value.dump());
    const auto x = value.get<std::int64_t>();
    if (x <= 0 || x > 1'000'000) Fail(field, "must be a positive size, got " + std::to_string(x));
    return static_cast<int>(x);
  }

  std::vector<double> Numbers(const json& parent, const std::string& key, const std::string& prefix,
                              size_t count) const {
    const std::string field = prefix + "." + key;
    const json& value = Member(parent, key, field);
    if (!value.is_array() || value.size() != count) {
      Fail(field, "must be an array of " + std::to_string(count) + " numbers");
    }
    std::vector<double> out;
    for (const json& x : value) {
      if (!x.is_number() || !std::isfinite(x.get<double>())) {
        Fail(field, "must be an array of " + std::to_string(count) + " finite numbers");
      }
      out.push_back(x.get<double>());
    }
    return out;
  }

  std::string String(const json& parent, const std::string& key, const std::string& prefix) const {
    const std::string field = prefix + "." + key;
    const json& value = Member(parent, key, field);
    if (!value.is_string() || value.get<std::string>().empty()) {
      Fail(field, "must be a non-empty string");
    }
    return value.get<std::string>();
  }

 private:
  static std::string Format(double x) {
    std::ostringstream out;
    out << x;
    return out.str();
  }
  const json& Member(const json& parent, const std::string& key, const std::string& field) const {
    const auto it = parent.find(key);
    if (it == parent.end()) Fail(field, "is missing");
    return *it;
  }

  std::filesystem::path file_;
};

CameraIntrinsics ReadIntrinsics(const FieldReader& in, const json& root, const std::string& name) {
  const json& j = in.Object(root, name, "");
  CameraIntrinsics c;
  c.width = in.PositiveInt(j, "width", name);
  c.height = in.PositiveInt(j, "height", name);
  c.fx = in.Positive(j, "fx", name);
  c.fy = in.Positive(j, "fy", name);
  c.cx = in.Number(j, "cx", name);
  c.cy = in.Number(j, "cy", name);
  const auto k = in.Numbers(j, "k", name, 3);
  c.k = {k[0], k[1], k[2]};
  return c;
}

json ObjectOr(const json& doc, const char* key) {
  const auto it = doc.find(key);
  return it != doc.end() && it->is_object() ? *it : json::object();
}

}  // namespace

nlohmann::json IntrinsicsJson(const CameraIntrinsics& c, nlohmann::json j) {
  j["width"] = c.width;
  j["height"] = c.height;
  j["fx"] = c.fx;
  j["fy"] = c.fy;
  j["cx"] = c.cx;
  j["cy"] = c.cy;
  j["k"] = {c.k[0], c.k[1], c.k[2]};
  return j;
}

ModuleDescription ParseModule(const std::string& text, const std::filesystem::path& path) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    const auto colon = what.find(": ");  // drop nlohmann's "[json.exception...] " prefix
    throw FileError(
        path, "invalid JSON: " + (colon == std::string::npos ? what : what.substr(colon + 2)));
  }
  if (!root.is_object()) throw FileError(path, "must hold a JSON object");
  const FieldReader in(path);
  ModuleDescription m;
  m.camera = ReadIntrinsics(in, root, "camera");
  m.projector = ReadIntrinsics(in, root, "projector");

  const json& extrinsics = in.Object(root, "projector_from_camera", "");
  const auto r = in.Numbers(extrinsics, "rotation", "projector_from_camera", 9);
  const auto t = in.Numbers(extrinsics, "translation_mm", "projector_from_camera", 3);
  Eigen::Matrix3d rotation;
  rotation << r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8];
  // Files written with ~6 significant digits are orthonormal to ~1e-6.
  const double error = (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm();
  if (error > 1e-4 || rotation.determinant() < 0.0) {
    in.Fail("projector_from_camera.rotation",
            "is not a rotation (R^T R - I = " + std::to_string(error) +
                ", det = " + std::to_string(rotation.determinant()) + ")");
  }
  m.projector_from_camera = Rigid3d(rotation, Eigen::Vector3d(t[0], t[1], t[2]));

  const json& pattern = in.Object(root, "pattern", "");
  m.pattern.matrix_path = in.String(pattern, "matrix", "pattern");
  m.pattern.pitch_px = in.Positive(pattern, "pitch_px", "pattern");
  m.pattern.spot_diameter_px = in.Positive(pattern, "spot_diameter_px", "pattern");
  if (m.pattern.spot_diameter_px > m.pattern.pitch_px) {
    in.Fail("pattern.spot_diameter_px", "must not exceed pattern.pitch_px");
  }
  const auto offset = in.Numbers(pattern, "offset_px", "pattern", 2);
  m.pattern.offset_px = {offset[0], offset[1]};
  m.source_json = text;
  ValidateFileContents(path, [&] { m.Check(); });
  return m;
}

LoadedModule LoadModule(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || !file)
    throw FileError(path, "cannot open file");
  std::ostringstream text;
  text << file.rdbuf();
  LoadedModule loaded;
  loaded.module = ParseModule(text.str(), path);
  std::filesystem::path matrix = loaded.module.pattern.matrix_path;
  if (matrix.is_relative()) matrix = path.parent_path() / matrix;
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
  json extrinsics = ObjectOr(doc, "projector_from_camera");
  const Eigen::Matrix3d r = m.projector_from_camera.RotationMatrix();
  extrinsics["rotation"] = {r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1),
                            r(1, 2), r(2, 0), r(2, 1), r(2, 2)};
  const Eigen::Vector3d& t = m.projector_from_camera.translation;
  extrinsics["translation_mm"] = {t.x(), t.y(), t.z()};
  doc["projector_from_camera"] = extrinsics;
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
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  std::ofstream file(path, std::ios::binary);
  if (!file) throw FileError(path, "cannot open for writing");
  file << ModuleToJson(module);
  if (!file.flush()) throw FileError(path, "write failed");
}

}  // namespace sewer3d
