#include "sewer3d/pipeline/workspace.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <nlohmann/json.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/file_stamp.hpp"
#include "sewer3d/run/capture_run.hpp"

#ifndef SEWER3D_VERSION
#error "SEWER3D_VERSION (CMake's PROJECT_VERSION) must be defined by the build"
#endif

namespace sewer3d {
namespace {

std::string UtcNow() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// Absolute and normalised, so that "run", "./run/" and "/abs/run" name the same run.
std::string RunName(const std::filesystem::path& run_folder) {
  // Links resolved: a run reached through a symbolic link is the same run.
  std::error_code ec;
  std::filesystem::path p = std::filesystem::weakly_canonical(run_folder, ec);
  if (ec) p = std::filesystem::absolute(run_folder).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();  // a trailing slash
  return p.string();
}

// The options that differ between two stage records, as "resolution_mm 0.2, now 0.5" (nested
// members by their path, "a.b"); the whole records when either is not JSON.
std::string OptionsChange(const std::string& before, const std::string& now) {
  const auto a = nlohmann::json::parse(before, nullptr, false);
  const auto b = nlohmann::json::parse(now, nullptr, false);
  if (a.is_discarded() || b.is_discarded()) return before + ", now " + now;
  const nlohmann::json fa = a.flatten();
  const nlohmann::json fb = b.flatten();
  std::string change;
  const auto add = [&](const std::string& key, const nlohmann::json& x, const nlohmann::json& y) {
    std::string name = key.empty() ? "options" : key.substr(1);
    std::replace(name.begin(), name.end(), '/', '.');
    change += (change.empty() ? "" : "; ") + name + " " + (x.is_null() ? "unset" : x.dump()) +
              ", now " + (y.is_null() ? "unset" : y.dump());
  };
  for (const auto& [key, value] : fa.items()) {
    if (!fb.contains(key) || fb[key] != value) add(key, value, fb.value(key, nlohmann::json()));
  }
  for (const auto& [key, value] : fb.items()) {
    if (!fa.contains(key)) add(key, nlohmann::json(), value);
  }
  return change.empty() ? before + ", now " + now : change;
}

// `folder`, unless it is checked out by CheckOutsideTheRun or lies inside another workspace
// (whose --force would delete it).
const std::filesystem::path& NotTheRun(const std::filesystem::path& folder,
                                       const std::filesystem::path& run_folder) {
  CheckOutsideTheRun(folder, run_folder, "the workspace (--out)");
  if (const auto owner = OwnerAbove(folder, {"workspace.json"}, false); !owner.empty()) {
    throw FileError(folder, "lies inside the workspace " + owner.parent_path().string() +
                                ": a workspace (--out) must be a folder of its own (a --force "
                                "there would remove it)");
  }
  return folder;
}

// The run's files besides its images (rgbd stamps those per acquisition), each with the first
// stage that reads it: the rig and pattern matrices (decoding, triangulation) and the image
// index (the texture's instants) feed rgbd; the odometry and the inclinometer feed register. Paths
// relative to the run folder, as rig.json names the matrices; a matrix shared by modules is listed
// once.
std::vector<std::pair<std::string, std::string>> RunFilesOf(const CaptureRun& run) {
  std::vector<std::pair<std::string, std::string>> files = {{"rig.json", "rgbd"},
                                                            {"acquisitions.csv", "rgbd"}};
  for (const RigModule& m : run.rig.modules) {
    const std::string matrix = m.module.pattern.matrix_path;
    const auto same = [&](const auto& f) { return f.first == matrix; };
    if (std::none_of(files.begin(), files.end(), same)) files.emplace_back(matrix, "rgbd");
  }
  files.emplace_back("odometry.csv", "register");
  if (!run.inclinometer.empty()) files.emplace_back("inclinometer.csv", "register");
  return files;
}

// Run files a run may lack, each with the first stage that reads it.
const std::pair<const char*, const char*> kOptionalRunFiles[] = {{"inclinometer.csv", "register"}};

}  // namespace

void CheckOutsideTheRun(const std::filesystem::path& folder,
                        const std::filesystem::path& run_folder, const std::string& role) {
  const std::filesystem::path run = RunName(run_folder), out = RunName(folder);
  const auto [end, at] = std::mismatch(run.begin(), run.end(), out.begin(), out.end());
  if (end == run.end()) {
    throw FileError(folder, std::string(at == out.end() ? "is" : "lies inside") +
                                " the capture run's own folder: " + role +
                                " must be another folder, so that the run stays as captured");
  }
  if (IsRegularFile(folder / "run.json")) {
    throw FileError(folder,
                    "holds a capture run (run.json): " + role + " must be a folder of its own");
  }
  // A folder above the run would hold the run, and every workspace beside it, as its own.
  if (std::mismatch(out.begin(), out.end(), run.begin(), run.end()).first == out.end()) {
    throw FileError(folder, "holds the capture run " + run_folder.string() + ": " + role +
                                " must be a folder of its own, beside the run");
  }
}

namespace {

// Stage outputs without workspace.json: nothing records which run, options or version made
// them, so no stage may resume from them or read them. What to say of them; empty if none.
std::string UnrecordedOutputs(const std::filesystem::path& folder) {
  std::string found;
  for (const std::string& stage : WorkspaceStageOrder()) {
    std::error_code ec;
    if (std::filesystem::is_directory(folder / OutputFolderName(stage), ec))
      found += (found.empty() ? "" : ", ") + OutputFolderName(stage) + "/";
  }
  if (found.empty()) return "";
  return "holds stage outputs (" + found +
         ") but no workspace.json, so nothing records which run and options made them; choose "
         "another --out, or remove those folders";
}

}  // namespace

void CheckWorkspaceOfRun(const std::filesystem::path& folder,
                         const std::filesystem::path& run_folder) {
  const std::filesystem::path record = folder / "workspace.json";
  if (!IsRegularFile(record)) {
    if (const std::string why = UnrecordedOutputs(folder); !why.empty())
      throw FileError(folder, why);
    return;
  }
  const std::string recorded = ReadWorkspaceRecord(record).run, run = RunName(run_folder);
  if (recorded != run) throw FileError(record, "workspace of run " + recorded + ", not of " + run);
}

std::filesystem::path OwnerAbove(const std::filesystem::path& folder,
                                 std::initializer_list<const char*> owners, bool including_folder) {
  const std::filesystem::path absolute = RunName(folder);
  std::filesystem::path up = including_folder ? absolute : absolute.parent_path();
  for (; !up.empty(); up = up.parent_path()) {
    for (const char* owner : owners) {
      if (IsRegularFile(up / owner)) return up / owner;
    }
    if (up == up.parent_path()) break;
  }
  return {};
}

std::string SoftwareVersion() { return SEWER3D_VERSION; }

std::string OutputFolderName(const std::string& stage) {
  if (stage == "register") return "registration";
  if (stage == "inspect") return "inspection";
  return stage;
}

namespace {

// The outputs a later stage reads, by stage (paths relative to the workspace).
std::vector<std::string> KeyOutputs(const std::string& stage) {
  if (stage == "register") return {"registration/poses.csv"};
  // Not the large maps: a stamp reads its file whole (displacement.tiff is GBs on a long run).
  if (stage == "model") return {"model/model.json", "model/coverage.png"};
  if (stage == "inspect") return {"inspection/observations.json", "inspection/profile.csv"};
  return {};
}

}  // namespace

const std::vector<std::string>& WorkspaceStageOrder() {
  static const std::vector<std::string> order = {"rgbd", "register", "model", "inspect", "report"};
  return order;
}

Workspace::Workspace(const std::filesystem::path& folder, const std::filesystem::path& run_folder)
    : folder_(NotTheRun(folder, run_folder)),
      lock_(folder),
      stale_temporaries_removed_(RemoveStaleTemporaries(folder)) {
  const std::string run = RunName(run_folder);
  if (IsRegularFile(RecordFile())) {
    record_ = ReadWorkspaceRecord(RecordFile());
    if (record_.run != run) {
      throw WorkspaceConflict(RecordFile().string() + ": workspace of run " + record_.run +
                              ", not of " + run + "; choose another --out");
    }
  } else if (const std::string why = UnrecordedOutputs(folder_); !why.empty()) {
    throw WorkspaceConflict(folder_.string() + ": " + why);
  }
  record_.run = run;
  record_.software_version = SoftwareVersion();
}

Workspace::Workspace(const std::filesystem::path& folder, const CaptureRun& run)
    : Workspace(folder, run.folder) {
  CheckRunFiles(run);
}

void Workspace::CheckBeginStage(const std::string& stage, const std::string& options_json,
                                bool force) const {
  const auto it = record_.stages.find(stage);
  const bool recorded = it != record_.stages.end();
  if (recorded && it->second.options_json == "{}" && options_json != "{}" && !force) {
    throw FileError(RecordFile(), "stages." + stage +
                                      ".options: empty, but the stage has options: the record "
                                      "was damaged; use --force to redo the stage");
  }
  if (recorded && it->second.options_json != options_json && !force) {
    throw WorkspaceConflict(RecordFile().string() + ": stage '" + stage +
                            "' was run with other options (" +
                            OptionsChange(it->second.options_json, options_json) +
                            "); use --force to redo it (its outputs are removed)");
  }
}

void Workspace::BeginStage(const std::string& stage, const std::string& options_json, bool force) {
  CheckBeginStage(stage, options_json, force);
  const bool recorded = record_.stages.count(stage) > 0;
  WorkspaceStage& s = record_.stages[stage];
  const bool afresh = force || s.stale;
  if (afresh) {
    RemoveFolder(StageFolder(OutputFolderName(stage)));
    MarkLaterStagesStale(stage);  // what they were made from is gone
  }
  if (afresh || !recorded || s.started_utc.empty()) s.started_utc = UtcNow();
  s.stale = false;
  s.options_json = options_json;
  s.done = false;
  s.done_utc.clear();
  s.software_version = SoftwareVersion();
  begun_[stage] = std::chrono::steady_clock::now();
  WriteWorkspaceRecord(RecordFile(), record_);
}

void Workspace::FinishStage(const std::string& stage, bool done,
                            const std::map<std::string, std::string>& notes, bool changed) {
  const auto it = record_.stages.find(stage);
  SEWER3D_CHECK(it != record_.stages.end(), "FinishStage without BeginStage: " + stage);
  it->second.done = done;
  it->second.done_utc = done ? UtcNow() : std::string();
  it->second.notes = notes;
  it->second.outputs.clear();
  for (const std::string& name : done ? KeyOutputs(stage) : std::vector<std::string>{}) {
    try {
      it->second.outputs[name] = StampFile(folder_ / name);
    } catch (const FileError&) {
      // not written (a stage with nothing to write): nothing to compare later
    }
  }
  const auto begun = begun_.find(stage);
  SEWER3D_CHECK(begun != begun_.end(), "FinishStage without BeginStage: " + stage);
  it->second.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begun->second).count();
  if (changed) MarkLaterStagesStale(stage);
  WriteWorkspaceRecord(RecordFile(), record_);
}

std::string Workspace::ChangedOutput(const std::string& stage) const {
  const auto it = record_.stages.find(stage);
  if (it == record_.stages.end()) return "";
  for (const auto& [name, stamp] : it->second.outputs) {
    if (!StillStamped(stamp, folder_ / name)) return (folder_ / name).string();
  }
  return "";
}

void Workspace::MarkLaterStagesStale(const std::string& stage) {
  const std::vector<std::string>& order = WorkspaceStageOrder();
  const auto at = std::find(order.begin(), order.end(), stage);
  if (at != order.end() && at + 1 != order.end()) MarkStaleFrom(*(at + 1));
}

std::vector<std::string> Workspace::MarkStaleFrom(const std::string& stage) {
  const std::vector<std::string>& order = WorkspaceStageOrder();
  std::vector<std::string> marked;
  for (auto s = std::find(order.begin(), order.end(), stage); s != order.end(); ++s) {
    const auto it = record_.stages.find(*s);
    if (it == record_.stages.end()) continue;
    it->second.done = false;
    it->second.done_utc.clear();
    it->second.stale = true;
    marked.push_back(*s);
  }
  return marked;
}

void Workspace::CheckRunFiles(const CaptureRun& run) {
  // An optional run file (the inclinometer) added after the stages ran, or removed, changes
  // what they would make; in a record without stamps (older workspaces) nothing is known.
  const bool stamped_before = !record_.run_files.empty();
  std::vector<std::pair<std::string, std::string>> files = RunFilesOf(run);
  for (const auto& [name, first_stage] : kOptionalRunFiles) {
    const auto listed = [&, n = name](const auto& f) { return f.first == n; };
    if (std::none_of(files.begin(), files.end(), listed) && record_.run_files.erase(name) > 0)
      NoteRunFileChange(run.folder / name, "removed", first_stage);
  }
  for (const auto& [name, first_stage] : files) {
    const std::filesystem::path file = run.folder / name;
    const auto recorded = record_.run_files.find(name);
    if (recorded != record_.run_files.end() && StillStamped(recorded->second, file)) continue;
    FileStamp stamp;
    try {
      stamp = StampFile(file);
    } catch (const FileError&) {
      continue;  // LoadRun read it a moment ago; a file gone since fails where it is used
    }
    const bool optional = std::any_of(std::begin(kOptionalRunFiles), std::end(kOptionalRunFiles),
                                      [&, n = name](const auto& f) { return f.first == n; });
    const bool was_recorded = recorded != record_.run_files.end();
    record_.run_files[name] = stamp;
    if (was_recorded || (optional && stamped_before))
      NoteRunFileChange(file, was_recorded ? "changed" : "added", first_stage);
  }
}

void Workspace::NoteRunFileChange(const std::filesystem::path& file, const std::string& what,
                                  const std::string& first_stage) {
  const std::vector<std::string> marked = MarkStaleFrom(first_stage);
  if (marked.empty()) return;
  std::string stages;
  for (const std::string& m : marked) stages += (stages.empty() ? "" : ", ") + m;
  run_file_changes_.push_back(file.string() + ": " + what +
                              " since the workspace's stages used it: " + stages + " start afresh");
}

void Workspace::RecordCommand(const std::string& name, const std::string& options_json, bool done,
                              double seconds, const std::map<std::string, std::string>& notes) {
  WorkspaceStage& s = record_.stages[name];
  if (s.started_utc.empty() || s.done) s.started_utc = UtcNow();
  s.options_json = options_json;
  s.done = done;
  s.done_utc = done ? UtcNow() : std::string();
  s.software_version = SoftwareVersion();
  s.seconds = seconds;
  s.notes = notes;
  WriteWorkspaceRecord(RecordFile(), record_);
}

}  // namespace sewer3d
