#pragma once
/// \file
/// Internal to io/: validated access to optional JSON fields with one-line FileErrors that
/// name the file and the field, and the render options' JSON form shared by the scene and
/// scenario files. Only io/*.cpp include this (it pulls in nlohmann/json).

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/sim/renderer.hpp"

namespace sewer3d {

class JsonReader {
 public:
  using json = nlohmann::json;
  explicit JsonReader(const std::filesystem::path& path) : path_(path) {}

  [[noreturn]] void Fail(const std::string& field, const std::string& problem) const {
    throw FileError(path_, "field '" + field + "' " + problem);
  }
  /// Parses text that must hold a JSON object.
  json ParseObject(const std::string& text) const {
    json j;
    try {
      j = json::parse(text);
    } catch (const json::parse_error& e) {
      throw FileError(path_, std::string("invalid JSON: ") + e.what());
    }
    if (!j.is_object()) throw FileError(path_, "must hold a JSON object");
    return j;
  }
  /// Rejects members not in `known` (typos must not be silently ignored).
  void OnlyKnown(const json& j, const std::string& prefix,
                 std::initializer_list<const char*> known) const {
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool found = false;
      for (const char* k : known) found = found || it.key() == k;
      if (!found) Fail(prefix + it.key(), "is not a known field");
    }
  }
  const json& Object(const json& j, const char* key, const std::string& prefix) const {
    static const json empty = json::object();
    const auto it = j.find(key);
    if (it == j.end()) return empty;
    if (!it->is_object()) Fail(prefix + key, "must be an object");
    return *it;
  }
  const json& Array(const json& j, const char* key, const std::string& prefix) const {
    static const json empty = json::array();
    const auto it = j.find(key);
    if (it == j.end()) return empty;
    if (!it->is_array()) Fail(prefix + key, "must be an array");
    return *it;
  }
  double Number(const json& j, const char* key, const std::string& prefix, double fallback) const {
    const auto it = j.find(key);
    if (it == j.end()) return fallback;
    if (!it->is_number() || !std::isfinite(it->get<double>()))
      Fail(prefix + key, "must be a finite number");
    return it->get<double>();
  }
  int Integer(const json& j, const char* key, const std::string& prefix, int fallback) const {
    const auto it = j.find(key);
    if (it == j.end()) return fallback;
    if (!it->is_number_integer()) Fail(prefix + key, "must be an integer");
    return it->get<int>();
  }
  bool Bool(const json& j, const char* key, const std::string& prefix, bool fallback) const {
    const auto it = j.find(key);
    if (it == j.end()) return fallback;
    if (!it->is_boolean()) Fail(prefix + key, "must be true or false");
    return it->get<bool>();
  }
  Eigen::Vector3d Vector(const json& j, const char* key, const Eigen::Vector3d& fallback) const {
    const auto it = j.find(key);
    if (it == j.end()) return fallback;
    if (!it->is_array() || it->size() != 3) Fail(key, "must be an array of 3 numbers");
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) {
      if (!(*it)[i].is_number()) Fail(key, "must be an array of 3 numbers");
      v[i] = (*it)[i].get<double>();
    }
    return v;
  }
  std::string Text(const json& j, const char* key, const std::string& prefix,
                   const std::string& fallback) const {
    const auto it = j.find(key);
    if (it == j.end()) return fallback;
    if (!it->is_string()) Fail(prefix + key, "must be a string");
    return it->get<std::string>();
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// The render options as JSON (what a scene.json or scenario file's "render" holds).
nlohmann::json RenderOptionsToJson(const RenderOptions& o);
/// Reads the members of a "render" object over `o` (absent members keep their values).
void ReadRenderOptions(const JsonReader& in, const nlohmann::json& j, const std::string& prefix,
                       RenderOptions& o);

/// A camera's intrinsics in the module file's form, over the fields `j` already holds.
nlohmann::json IntrinsicsJson(const CameraIntrinsics& c,
                              nlohmann::json j = nlohmann::json::object());

const char* MaterialName(Material m);
/// Throws via `in` when the name is not a material.
Material ParseMaterial(const JsonReader& in, const std::string& name, const std::string& field);

}  // namespace sewer3d
