#pragma once
/// \file
/// Internal to the file readers (io/, simio/): validated access to JSON fields with one-line
/// FileErrors that name the file and the dotted field ("PATH: field 'camera.fx' must be
/// positive, got -1"). One reader for every JSON file sewer3d reads; it pulls in
/// nlohmann/json, so only .cpp files include it.
///
/// Field prefixes end with a dot ("carrier.") or are empty. Getters with a fallback treat a
/// missing member as "use the fallback"; getters without one require the member.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/io/file_error.hpp"

namespace sewer3d {

class JsonReader {
 public:
  using json = nlohmann::json;
  explicit JsonReader(std::filesystem::path path) : path_(std::move(path)) {}

  [[noreturn]] void Fail(const std::string& field, const std::string& problem) const;
  /// Parses text that must hold a JSON object ("invalid JSON: …" otherwise).
  json ParseObject(const std::string& text) const;
  /// Rejects members not in `known` (typos must not be silently ignored).
  void OnlyKnown(const json& j, const std::string& prefix,
                 std::initializer_list<const char*> known) const;
  /// For files other tools extend (module, rig, run): members not in `known` are kept, but one
  /// within an edit or two of a known name is a typo (an optional member silently defaulted)
  /// and refused with the name it resembles.
  void NoNearMisses(const json& j, const std::string& prefix,
                    std::initializer_list<const char*> known) const;

  // Optional members: the fallback when missing, an error when of the wrong type.
  const json& Object(const json& j, const char* key, const std::string& prefix) const;
  const json& Array(const json& j, const char* key, const std::string& prefix) const;
  double Number(const json& j, const char* key, const std::string& prefix, double fallback) const;
  /// An integer that fits an int exactly (1e10 or 2.5 are errors, not wrapped or cut).
  int Integer(const json& j, const char* key, const std::string& prefix, int fallback) const;
  /// A seed: an integer 0 .. 2^64 − 1, kept exactly (never through a double).
  std::uint64_t Seed(const json& j, const char* key, const std::string& prefix,
                     std::uint64_t fallback) const;
  bool Bool(const json& j, const char* key, const std::string& prefix, bool fallback) const;
  std::string Text(const json& j, const char* key, const std::string& prefix,
                   const std::string& fallback) const;
  Eigen::Vector3d Vector(const json& j, const char* key, const std::string& prefix,
                         const Eigen::Vector3d& fallback) const;

  // Required members.
  const json& RequiredObject(const json& j, const char* key, const std::string& prefix) const;
  double Number(const json& j, const char* key, const std::string& prefix) const;
  double Positive(const json& j, const char* key, const std::string& prefix) const;
  /// An integer in 1 .. 1 000 000 (an image or array size).
  int PositiveSize(const json& j, const char* key, const std::string& prefix) const;
  /// A non-empty string.
  std::string Text(const json& j, const char* key, const std::string& prefix) const;
  /// An array of exactly `count` finite numbers.
  std::vector<double> Numbers(const json& j, const char* key, const std::string& prefix,
                              size_t count) const;
  /// A rotation as 9 numbers, row-major: orthonormal within 1e-4 (files written with ~6
  /// significant digits) and proper (det > 0).
  Eigen::Matrix3d Rotation(const json& j, const char* key, const std::string& prefix) const;
  /// {"rotation": [9], "translation_mm": [3]}: b_from_a maps a point X to R X + t.
  Rigid3d Pose(const json& j, const char* key, const std::string& prefix) const;

  const std::filesystem::path& path() const { return path_; }

 private:
  const json& Member(const json& j, const char* key, const std::string& prefix) const;

  std::filesystem::path path_;
};

/// What sewer3d file a JSON object is, from its "format" member or its top-level members ("a
/// rig file (rig.json)", "a module file"); empty when it is none of them. For refusals of a file
/// given where another kind belongs.
std::string KnownFileKind(const nlohmann::json& j);

/// A readable account of a JSON syntax error nlohmann stopped at (`byte`, counted from 1, and
/// its message `what`): the line and column, the text before it and what JSON wanted there; for
/// a file that does not begin like JSON at all (a CSV, an image) just that.
std::string JsonSyntaxProblem(const std::string& text, std::size_t byte, const std::string& what);

/// The JSON form JsonReader::Pose reads, over the members `j` already holds.
nlohmann::json PoseToJson(const Rigid3d& pose, nlohmann::json j = nlohmann::json::object());

/// A camera's intrinsics in the module file's form, over the fields `j` already holds.
nlohmann::json IntrinsicsJson(const CameraIntrinsics& c,
                              nlohmann::json j = nlohmann::json::object());

}  // namespace sewer3d
