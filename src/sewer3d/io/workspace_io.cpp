#include "sewer3d/io/workspace_io.hpp"

#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_stamp_json.hpp"
#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {

using nlohmann::json;

namespace {

// The object `key` of `parent`: file name -> stamp.
std::map<std::string, FileStamp> Stamps(const JsonReader& reader, const json& parent,
                                        const char* key, const std::string& prefix) {
  std::map<std::string, FileStamp> stamps;
  for (const auto& [name, stamp] : reader.Object(parent, key, prefix).items()) {
    try {
      stamps[name] = StampFromJson(stamp);
    } catch (const std::exception&) {
      reader.Fail(prefix + key + "." + std::string(name),
                  "must be {\"bytes\": N, \"mtime_ns\": N, \"hash\": \"hex\"}");
    }
  }
  return stamps;
}

}  // namespace

std::string WorkspaceToJson(const WorkspaceRecord& record) {
  json stages = json::object();
  for (const auto& [name, s] : record.stages) {
    json stage;
    stage["options"] = json::parse(s.options_json);
    stage["done"] = s.done;
    if (s.stale) stage["stale"] = true;
    stage["started_utc"] = s.started_utc;
    stage["done_utc"] = s.done_utc.empty() ? json(nullptr) : json(s.done_utc);
    stage["software_version"] = s.software_version;
    stage["seconds"] = s.seconds;
    stage["notes"] = s.notes;
    if (!s.outputs.empty()) {
      json outputs = json::object();
      for (const auto& [name, stamp] : s.outputs) outputs[name] = StampToJson(stamp);
      stage["outputs"] = outputs;
    }
    stages[name] = stage;
  }
  json j = {{"format", "sewer3d-workspace"},
            {"version", 1},
            {"run", record.run},
            {"software_version", record.software_version},
            {"stages", stages}};
  if (!record.run_files.empty()) {
    json files = json::object();
    for (const auto& [name, stamp] : record.run_files) files[name] = StampToJson(stamp);
    j["run_files"] = files;
  }
  return j.dump(2) + "\n";
}

WorkspaceRecord WorkspaceFromJson(const std::string& text, const std::filesystem::path& path) {
  const JsonReader reader(path);
  const json j = reader.ParseObject(text);
  if (reader.Text(j, "format", "") != "sewer3d-workspace")
    reader.Fail("format", "must be \"sewer3d-workspace\"");
  if (reader.Integer(j, "version", "", 0) != 1) reader.Fail("version", "must be 1");
  WorkspaceRecord record;
  record.run = reader.Text(j, "run", "");
  record.software_version = reader.Text(j, "software_version", "", "");
  const json& stages = reader.Object(j, "stages", "");
  for (const auto& [name, s] : stages.items()) {
    const std::string prefix = "stages." + name + ".";
    if (!s.is_object()) reader.Fail("stages." + name, "must be an object");
    WorkspaceStage stage;
    stage.options_json = reader.RequiredObject(s, "options", prefix).dump();
    stage.done = reader.Bool(s, "done", prefix, false);
    stage.stale = reader.Bool(s, "stale", prefix, false);
    stage.started_utc = reader.Text(s, "started_utc", prefix, "");
    if (s.contains("done_utc") && !s["done_utc"].is_null())
      stage.done_utc = reader.Text(s, "done_utc", prefix, "");
    stage.software_version = reader.Text(s, "software_version", prefix, "");
    stage.seconds = reader.Number(s, "seconds", prefix, 0.0);
    if (!(stage.seconds >= 0.0 && stage.seconds <= 1e9))  // a wall time: 0 .. 30 years
      reader.Fail(prefix + "seconds", "must be 0 to 1e9 (a wall time in seconds)");
    for (const auto& [key, value] : reader.Object(s, "notes", prefix).items()) {
      if (!value.is_string()) reader.Fail(prefix + "notes." + std::string(key), "must be a string");
      stage.notes[key] = value.get<std::string>();
    }
    if (s.contains("outputs")) stage.outputs = Stamps(reader, s, "outputs", prefix);
    record.stages[name] = stage;
  }
  if (j.contains("run_files")) record.run_files = Stamps(reader, j, "run_files", "");
  return record;
}

void WriteWorkspaceRecord(const std::filesystem::path& path, const WorkspaceRecord& record) {
  WriteTextFileAtomically(path, WorkspaceToJson(record));
}

WorkspaceRecord ReadWorkspaceRecord(const std::filesystem::path& path) {
  return WorkspaceFromJson(ReadTextFile(path), path);
}

}  // namespace sewer3d
