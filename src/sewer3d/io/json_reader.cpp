#include "sewer3d/io/json_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <sstream>
#include <vector>

#include "sewer3d/core/edit_distance.hpp"

namespace sewer3d {
namespace {

std::string Format(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

// At most the last 30 characters of text[from, end) with each run of white space as one space
// and other control characters as '?': what the reader had read when it stopped.
std::string TextBefore(const std::string& text, std::size_t from, std::size_t end) {
  std::string near;
  for (std::size_t i = from; i < end; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    const bool space = c == ' ' || c == '\t' || c == '\r' || c == '\n';
    if (space && (near.empty() || near.back() == ' ')) continue;
    near += space ? ' ' : c < 0x20 ? '?' : static_cast<char>(c);
  }
  if (near.size() > 30) near = "…" + near.substr(near.size() - 30);
  return near;
}

}  // namespace

std::string JsonSyntaxProblem(const std::string& text, std::size_t byte, const std::string& what) {
  const std::size_t bom = text.starts_with("\xEF\xBB\xBF") ? 3 : 0;
  const std::size_t first = text.find_first_not_of(" \t\r\n", bom);
  if (first != std::string::npos && text[first] != '{' && text[first] != '[') {
    const std::size_t line_end = std::min(text.find_first_of("\r\n", first), first + 20);
    const std::string begin = TextBefore(text, first, std::min(text.size(), line_end));
    return "is not JSON (it begins with \"" + begin + "\"; a JSON file begins with '{')";
  }
  // nlohmann counts the byte it stopped at from 1; the line and column from it.
  const std::size_t at = std::min(text.size(), byte > 0 ? byte - 1 : 0);
  const std::size_t line = 1 + std::count(text.begin(), text.begin() + at, '\n');
  const std::size_t line_start = at == 0 ? std::string::npos : text.rfind('\n', at - 1);
  const std::size_t column = at - (line_start == std::string::npos ? 0 : line_start + 1) + 1;
  std::string reason;
  if (what.find("unexpected end of input") != std::string::npos) {
    reason = "the file ends inside an object, array or string (cut short?)";
  } else if (what.find("control character") != std::string::npos) {
    reason = "a string holds a raw line break or control character (a quote missing?)";
  } else if (what.find("object key") != std::string::npos) {
    reason = "a member name must follow, in double quotes (a comma too many, or single quotes?)";
  } else if (what.find("invalid literal") != std::string::npos) {
    reason = "not a JSON value (JSON has no comments, single quotes or bare words)";
  } else {
    const std::size_t dash = what.find(" - ");
    reason = dash == std::string::npos ? "syntax error" : what.substr(dash + 3);
    reason = reason.substr(0, reason.find("; last read"));
  }
  std::string found = "the end";
  if (at < text.size()) {
    const auto c = static_cast<unsigned char>(text[at]);
    found = c == '\n' || c == '\r'  ? "a line break"
            : c == ' ' || c == '\t' ? "a space"
            : c < 0x20              ? "a control character"
                                    : "'" + TextBefore(text, at, at + 1) + "'";
  }
  return "invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(column) +
         " (" + found + " after \"" + TextBefore(text, at > 60 ? at - 60 : 0, at) +
         "\"): " + reason;
}

void JsonReader::Fail(const std::string& field, const std::string& problem) const {
  throw FileError(path_, "field '" + field + "' " + problem);
}

JsonReader::json JsonReader::ParseObject(const std::string& text) const {
  // nlohmann reads a NUL as the end of the input ("unexpected end of input"): name it.
  if (const auto nul = text.find('\0'); nul != std::string::npos)
    throw FileError(path_, "a NUL byte at offset " + std::to_string(nul) + ": not a text file");
  json j;
  // A member given twice is an error: nlohmann would keep the last one without a word. One set
  // of keys per object being read, innermost last; the path names the member.
  std::vector<std::set<std::string>> keys;
  std::vector<std::string> path;
  std::string duplicate;
  const json::parser_callback_t check = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        keys.emplace_back();
        path.emplace_back();
        break;
      case json::parse_event_t::key:
        if (!keys.back().insert(parsed.get<std::string>()).second && duplicate.empty()) {
          for (std::size_t k = 0; k + 1 < path.size(); ++k) duplicate += path[k] + ".";
          duplicate += parsed.get<std::string>();
        }
        path.back() = parsed.get<std::string>();
        break;
      case json::parse_event_t::object_end:
        keys.pop_back();
        path.pop_back();
        break;
      default:
        break;
    }
    return true;
  };
  try {
    j = json::parse(text, check);
  } catch (const json::parse_error& e) {
    throw FileError(path_, JsonSyntaxProblem(text, e.byte, e.what()));
  } catch (const json::exception& e) {  // out_of_range for a number like 1e400
    // Without nlohmann's "[json.exception...] " prefix.
    const std::string what = e.what();
    const auto cut = what.find("] ");
    throw FileError(path_,
                    "invalid JSON: " + (cut == std::string::npos ? what : what.substr(cut + 2)));
  }
  if (!duplicate.empty())
    throw FileError(path_, "field '" + duplicate + "' is given twice (which one is meant?)");
  if (!j.is_object()) throw FileError(path_, "must hold a JSON object");
  return j;
}

void JsonReader::OnlyKnown(const json& j, const std::string& prefix,
                           std::initializer_list<const char*> known) const {
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool found = false;
    for (const char* k : known) found = found || it.key() == k;
    if (!found) Fail(prefix + it.key(), "is not a known field");
  }
}

void JsonReader::NoNearMisses(const json& j, const std::string& prefix,
                              std::initializer_list<const char*> known) const {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    bool found = false;
    for (const char* k : known) found = found || key == k;
    if (found) continue;
    for (const char* k : known) {
      const std::string name(k);
      // One edit in a short name, two in a longer one: "clock_hh", "Clock_h", "pitch_pc".
      const size_t allowed = std::min(key.size(), name.size()) <= 4 ? 1 : 2;
      if (EditDistance(key, name) <= allowed) {
        std::string problem = "is not a field sewer3d reads; did you mean '";
        problem += prefix;
        problem += name;
        problem += "'? (fields far from every known name are kept as they are)";
        Fail(prefix + key, problem);
      }
    }
  }
}

const JsonReader::json& JsonReader::Object(const json& j, const char* key,
                                           const std::string& prefix) const {
  static const json empty = json::object();
  const auto it = j.find(key);
  if (it == j.end()) return empty;
  if (!it->is_object()) Fail(prefix + key, "must be an object");
  return *it;
}

const JsonReader::json& JsonReader::Array(const json& j, const char* key,
                                          const std::string& prefix) const {
  static const json empty = json::array();
  const auto it = j.find(key);
  if (it == j.end()) return empty;
  if (!it->is_array()) Fail(prefix + key, "must be an array");
  return *it;
}

double JsonReader::Number(const json& j, const char* key, const std::string& prefix,
                          double fallback) const {
  return j.contains(key) ? Number(j, key, prefix) : fallback;
}

int JsonReader::Integer(const json& j, const char* key, const std::string& prefix,
                        int fallback) const {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  const bool fits = it->is_number_unsigned()
                        ? it->get<std::uint64_t>() <= std::uint64_t{std::numeric_limits<int>::max()}
                        : it->is_number_integer() &&
                              it->get<std::int64_t>() >= std::numeric_limits<int>::min() &&
                              it->get<std::int64_t>() <= std::numeric_limits<int>::max();
  if (!fits) Fail(prefix + key, "must be an integer within ±2147483647, got " + it->dump());
  return it->get<int>();
}

std::uint64_t JsonReader::Seed(const json& j, const char* key, const std::string& prefix,
                               std::uint64_t fallback) const {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  const bool whole =
      it->is_number_unsigned() || (it->is_number_integer() && it->get<std::int64_t>() >= 0);
  if (!whole) Fail(prefix + key, "must be an integer 0..18446744073709551615, got " + it->dump());
  return it->get<std::uint64_t>();
}

bool JsonReader::Bool(const json& j, const char* key, const std::string& prefix,
                      bool fallback) const {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  if (!it->is_boolean()) Fail(prefix + key, "must be true or false");
  return it->get<bool>();
}

std::string JsonReader::Text(const json& j, const char* key, const std::string& prefix,
                             const std::string& fallback) const {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  if (!it->is_string()) Fail(prefix + key, "must be a string");
  if (it->get<std::string>().find('\0') != std::string::npos)
    Fail(prefix + key, "holds a NUL character (\\u0000)");
  return it->get<std::string>();
}

Eigen::Vector3d JsonReader::Vector(const json& j, const char* key, const std::string& prefix,
                                   const Eigen::Vector3d& fallback) const {
  if (!j.contains(key)) return fallback;
  const auto v = Numbers(j, key, prefix, 3);
  return {v[0], v[1], v[2]};
}

const JsonReader::json& JsonReader::Member(const json& j, const char* key,
                                           const std::string& prefix) const {
  const auto it = j.find(key);
  if (it == j.end()) Fail(prefix + key, "is missing");
  return *it;
}

const JsonReader::json& JsonReader::RequiredObject(const json& j, const char* key,
                                                   const std::string& prefix) const {
  const json& value = Member(j, key, prefix);
  if (!value.is_object()) Fail(prefix + key, "must be an object");
  return value;
}

double JsonReader::Number(const json& j, const char* key, const std::string& prefix) const {
  const json& value = Member(j, key, prefix);
  if (!value.is_number()) Fail(prefix + key, "must be a number, got " + value.dump());
  const double x = value.get<double>();
  if (!std::isfinite(x)) Fail(prefix + key, "must be finite");
  return x;
}

double JsonReader::Positive(const json& j, const char* key, const std::string& prefix) const {
  const double x = Number(j, key, prefix);
  if (!(x > 0.0)) Fail(prefix + key, "must be positive, got " + Format(x));
  return x;
}

int JsonReader::PositiveSize(const json& j, const char* key, const std::string& prefix) const {
  const json& value = Member(j, key, prefix);
  if (!value.is_number_integer()) Fail(prefix + key, "must be an integer, got " + value.dump());
  constexpr std::int64_t kMax = 1'000'000;
  // A huge unsigned value must not wrap into the range.
  const std::int64_t x = value.is_number_unsigned() && value.get<std::uint64_t>() > kMax
                             ? -1
                             : value.get<std::int64_t>();
  if (x <= 0 || x > kMax)
    Fail(prefix + key, "must be a positive size up to 1000000, got " + value.dump());
  return static_cast<int>(x);
}

std::string JsonReader::Text(const json& j, const char* key, const std::string& prefix) const {
  const json& value = Member(j, key, prefix);
  if (!value.is_string() || value.get<std::string>().empty())
    Fail(prefix + key, "must be a non-empty string");
  if (value.get<std::string>().find('\0') != std::string::npos)
    Fail(prefix + key, "holds a NUL character (\\u0000)");
  return value.get<std::string>();
}

std::vector<double> JsonReader::Numbers(const json& j, const char* key, const std::string& prefix,
                                        size_t count) const {
  const json& value = Member(j, key, prefix);
  const std::string what = "must be an array of " + std::to_string(count) + " finite numbers";
  if (!value.is_array() || value.size() != count) Fail(prefix + key, what);
  std::vector<double> out;
  for (const json& x : value) {
    if (!x.is_number() || !std::isfinite(x.get<double>())) Fail(prefix + key, what);
    out.push_back(x.get<double>());
  }
  return out;
}

Eigen::Matrix3d JsonReader::Rotation(const json& j, const char* key,
                                     const std::string& prefix) const {
  const auto r = Numbers(j, key, prefix, 9);
  Eigen::Matrix3d rotation;
  rotation << r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8];
  const double error = (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm();
  if (error > 1e-4 || rotation.determinant() < 0.0) {
    Fail(prefix + key, "is not a rotation (R^T R - I = " + Format(error) +
                           ", det = " + Format(rotation.determinant()) + ")");
  }
  return rotation;
}

Rigid3d JsonReader::Pose(const json& j, const char* key, const std::string& prefix) const {
  const json& pose = RequiredObject(j, key, prefix);
  const std::string inner = prefix + key + ".";
  const Eigen::Matrix3d rotation = Rotation(pose, "rotation", inner);
  const auto t = Numbers(pose, "translation_mm", inner, 3);
  return Rigid3d(rotation, Eigen::Vector3d(t[0], t[1], t[2]));
}

nlohmann::json PoseToJson(const Rigid3d& pose, nlohmann::json j) {
  const Eigen::Matrix3d r = pose.RotationMatrix();
  j["rotation"] = {r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)};
  const Eigen::Vector3d& t = pose.translation;
  j["translation_mm"] = {t.x(), t.y(), t.z()};
  return j;
}

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

std::string KnownFileKind(const nlohmann::json& j) {
  if (!j.is_object()) return {};
  static const std::pair<const char*, const char*> kFormats[] = {
      {"sewer3d-rig", "a rig file (rig.json)"},
      {"sewer3d-run", "a capture run's run.json"},
      {"sewer3d pipe model", "a pipe model's model.json"},
      {"sewer3d-observations", "an inspection's observations.json"},
      {"sewer3d-workspace", "a workspace's workspace.json"},
      {"sewer3d-reference-light", "a reference-light file"}};
  const auto format = j.find("format");
  for (const auto& [name, kind] : kFormats) {
    if (format != j.end() && *format == nlohmann::json(name)) return kind;
  }
  if (j.contains("camera") && j.contains("projector")) return "a module file";
  if (j.contains("pipe") || j.contains("motion")) return "a scenario file";
  if (j.contains("scene") || (j.contains("type") && j.contains("material"))) return "a scene file";
  return {};
}

}  // namespace sewer3d
