#include "sewer3d/report/evaluation_tables.hpp"

#include <fmt/core.h>

#include <nlohmann/json.hpp>
#include <set>
#include <vector>

#include "sewer3d/report/html.hpp"

namespace sewer3d {
namespace {

using Json = nlohmann::json;
using Rows = std::vector<std::vector<std::string>>;

std::string Scalar(const Json& v) {
  if (v.is_number_float()) return fmt::format("{:.4g}", v.get<double>());
  if (v.is_string()) return v.get<std::string>();
  if (v.is_null()) return "–";
  return v.dump();
}

bool IsScalarArray(const Json& v) {
  if (!v.is_array()) return false;
  for (const Json& e : v) {
    if (e.is_structured()) return false;
  }
  return true;
}

std::string ObjectArrayTable(const std::string& title, const Json& array) {
  std::vector<std::string> keys;
  std::set<std::string> seen;
  for (const Json& e : array) {
    if (!e.is_object()) continue;
    for (const auto& [k, v] : e.items()) {
      if (!v.is_structured() && seen.insert(k).second) keys.push_back(k);
    }
  }
  Rows rows;
  for (const Json& e : array) {
    std::vector<std::string> row;
    for (const std::string& k : keys)
      row.push_back(e.is_object() && e.contains(k) ? Scalar(e[k]) : "");
    rows.push_back(row);
  }
  return "<h4>" + html::Escape(title) + "</h4>" + html::Table(keys, rows, "figures");
}

// Scalars (and scalar arrays) into `rows` as "path" → value; arrays of objects into `tables`.
void Flatten(const Json& j, const std::string& path, Rows& rows, std::string& tables) {
  for (const auto& [k, v] : j.items()) {
    std::string name = path;
    if (!name.empty()) name += " / ";
    name += k;
    if (v.is_object()) {
      Flatten(v, name, rows, tables);
    } else if (IsScalarArray(v)) {
      std::string joined;
      for (const Json& e : v) {
        if (!joined.empty()) joined += ", ";
        joined += Scalar(e);
      }
      rows.push_back({name, joined});
    } else if (v.is_array()) {
      tables += ObjectArrayTable(name, v);
    } else {
      rows.push_back({name, Scalar(v)});
    }
  }
}

}  // namespace

std::string EvaluationTables(const std::string& name, const std::string& json_text) {
  std::string out = "<h3>" + html::Escape(name) + "</h3>\n";
  const Json j = Json::parse(json_text, nullptr, false);
  if (j.is_discarded() || !j.is_object())
    return out + html::Note("evaluation.json of " + name + " is not a JSON object; not shown.");
  Rows rows;
  std::string tables;
  Flatten(j, "", rows, tables);
  if (!rows.empty()) out += html::Table({"figure", "value"}, rows, "figures");
  return out + tables;
}

}  // namespace sewer3d
