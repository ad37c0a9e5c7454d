#include "sewer3d/io/run_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "sewer3d/io/csv.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/inclinometer_io.hpp"
#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kIndexHeader = "module,counter,image,time_s,exposure_ms,file";
constexpr const char* kOdometryHeader = "time_s,distance_mm";
// Plausible bounds for a cable counter: beyond them a value is a corrupt field, not a run.
constexpr double kMaxOdometryMm = 1e7;  // 10 km of cable
constexpr double kMaxTimeS = 1e7;       // about 115 days
// 10 µs: the shortest exposure of machine-vision sensors; below it the light collected is
// nothing, and an exposure of 0 is no image.
constexpr double kMinExposureMs = 0.01;
constexpr double kMaxExposureMs = 1000.0;  // a second: no moving inspection camera exposes longer

// A file name from the index must stay inside the run folder.
bool InsideRun(const std::string& file) {
  const fs::path p(file);
  if (file.empty() || p.is_absolute()) return false;
  for (const auto& part : p) {
    if (part == "..") return false;
  }
  return true;
}

// The median time between a module's consecutive pattern images; 0 where no module has two.
double MedianPatternGap(const std::vector<RunImage>& images) {
  std::map<int, std::vector<std::pair<int, double>>> patterns;  // module: (counter, time)
  for (const RunImage& image : images) {
    if (image.kind == ImageKind::kPattern)
      patterns[image.module].emplace_back(image.counter, image.time_s);
  }
  std::vector<double> gaps;
  for (auto& [module, shots] : patterns) {
    std::sort(shots.begin(), shots.end());
    for (size_t i = 1; i < shots.size(); ++i) {
      const int counters = shots[i].first - shots[i - 1].first;
      gaps.push_back((shots[i].second - shots[i - 1].second) / counters);
    }
  }
  if (gaps.empty()) return 0.0;
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  return gaps[gaps.size() / 2];
}

// run.json's acquisition_period_s, where it gives one, must be that of the index: the median
// time between a module's consecutive pattern images, within a factor of 2.
void CheckAcquisitionPeriod(const fs::path& path, double period_s, double median) {
  if (period_s <= 0.0 || median <= 0.0) return;  // not known
  if (period_s < 0.5 * median || period_s > 2.0 * median) {
    throw FileError(path, fmt::format("acquisition_period_s is {:g} s, but acquisitions.csv has a "
                                      "module's acquisitions {:.3g} s apart (median)",
                                      period_s, median));
  }
}

// A texture image is shot just before or after its pattern image: more than half an acquisition
// period away (1 s where the period is not known), it shows the wall somewhere else.
void CheckTripletTimes(const fs::path& index, double period_s,
                       const std::vector<RunImage>& images) {
  const double limit_s = period_s > 0.0 ? 0.5 * period_s : 1.0;
  std::map<std::pair<int, int>, double> pattern_time;  // (module, counter): time
  for (const RunImage& image : images) {
    if (image.kind == ImageKind::kPattern)
      pattern_time[{image.module, image.counter}] = image.time_s;
  }
  for (const RunImage& image : images) {
    const auto pattern = pattern_time.find({image.module, image.counter});
    if (image.kind == ImageKind::kPattern || pattern == pattern_time.end()) continue;
    const double gap_s = std::abs(image.time_s - pattern->second);
    if (gap_s > limit_s) {
      throw FileError(index, fmt::format("{} is {:g} s from its pattern image, more than {:.3g} s "
                                         "({}): it was not shot with it",
                                         image.file, gap_s, limit_s,
                                         period_s > 0.0 ? "half the time between acquisitions"
                                                        : "the period is not known"));
    }
  }
}

// run.json's counts, where it gives them, must match the rig and the index of a complete run.
void CheckRunCounts(const fs::path& path, const RunCounts& counts, const CaptureRun& run) {
  const auto modules = static_cast<int>(run.rig.modules.size());
  if (counts.modules >= 0 && counts.modules != modules) {
    throw FileError(
        path, fmt::format("modules: says {}, rig.json describes {}", counts.modules, modules));
  }
  // The modules first: a wrong module count makes the image count look wrong too.
  const std::int64_t planned = std::int64_t{3} * counts.modules * counts.acquisitions;
  if (counts.modules >= 0 && counts.acquisitions >= 0 && counts.images >= 0 &&
      counts.images != planned) {
    throw FileError(path, fmt::format("field 'images' must be 3 x modules x acquisitions ({}), "
                                      "got {}",
                                      planned, counts.images));
  }
  const auto images = static_cast<int>(run.images.size());
  if (run.info.complete && counts.images >= 0 && counts.images != images) {
    throw FileError(
        path, fmt::format("images: says {}, acquisitions.csv lists {}", counts.images, images));
  }
}

}  // namespace

std::string RigToJson(const Rig& rig) {
  json j;
  j["format"] = "sewer3d-rig";
  j["version"] = 1;
  j["carrier"] = {{"diameter_mm", rig.carrier_diameter_mm}, {"length_mm", rig.carrier_length_mm}};
  j["modules"] = json::array();
  for (const RigModule& m : rig.modules) {
    j["modules"].push_back({{"name", m.name},
                            {"clock_h", m.clock_h},
                            {"module", json::parse(ModuleToJson(m.module))},
                            {"carrier_from_camera", PoseToJson(m.carrier_from_camera)}});
  }
  return j.dump(2) + "\n";
}

void WriteRig(const fs::path& path, const Rig& rig) { WriteTextFile(path, RigToJson(rig)); }

LoadedRig ReadRig(const fs::path& path) {
  const JsonReader in(path);
  const json j = in.ParseObject(ReadTextFile(path));
  in.NoNearMisses(j, "", {"format", "version", "carrier", "modules"});
  if (in.Text(j, "format", "", "") != "sewer3d-rig") in.Fail("format", "must be \"sewer3d-rig\"");
  if (in.Integer(j, "version", "", 1) != 1) in.Fail("version", "must be 1");
  LoadedRig out;
  const json& carrier = in.Object(j, "carrier", "");
  in.NoNearMisses(carrier, "carrier.", {"diameter_mm", "length_mm"});
  out.rig.carrier_diameter_mm = in.Number(carrier, "diameter_mm", "carrier.", 150.0);
  out.rig.carrier_length_mm = in.Number(carrier, "length_mm", "carrier.", 600.0);
  const json& modules = in.Array(j, "modules", "");
  if (modules.empty()) in.Fail("modules", "must list at least one module");
  for (size_t i = 0; i < modules.size(); ++i) {
    const std::string p = "modules[" + std::to_string(i) + "].";
    const json& m = modules[i];
    if (!m.is_object()) in.Fail(p, "must be an object with module and carrier_from_camera");
    in.NoNearMisses(m, p, {"name", "clock_h", "module", "carrier_from_camera"});
    RigModule rm;
    rm.name = in.Text(m, "name", p, fmt::format("m{}", i));
    rm.clock_h = in.Number(m, "clock_h", p, 12.0);
    try {
      rm.module = ParseModule(in.RequiredObject(m, "module", p).dump(), path);
    } catch (const FileError& e) {
      throw FileError(path,
                      p + "module: " + std::string(e.what()).substr(path.string().size() + 2));
    }
    rm.carrier_from_camera = in.Pose(m, "carrier_from_camera", p);
    fs::path matrix = rm.module.pattern.matrix_path;
    if (matrix.is_relative()) matrix = path.parent_path() / matrix;
    try {
      out.patterns.push_back(ReadPatternMatrix(matrix));
    } catch (const FileError& e) {  // the field that names the file, then the file's problem
      throw FileError(path, p + "module.pattern.matrix: " + e.what());
    }
    out.rig.modules.push_back(rm);
  }
  ValidateFileContents(path, [&] { out.rig.Check(); });
  return out;
}

void WriteRunInfo(const fs::path& path, const RunInfo& info, const RunCounts& counts) {
  const json j{{"format", "sewer3d-run"},
               {"version", 1},
               {"complete", info.complete},
               {"created_by", info.created_by},
               {"scenario", info.scenario},
               {"seed", info.seed},
               {"rig", "rig.json"},
               {"index", "acquisitions.csv"},
               {"odometry", "odometry.csv"},
               {"modules", counts.modules},
               {"acquisitions", counts.acquisitions},
               {"images", counts.images},
               {"acquisition_period_s",
                info.acquisition_period_s > 0.0 ? json(info.acquisition_period_s) : json(nullptr)},
               {"color_filter", info.color_filter},
               {"simulation_seconds", counts.simulation_seconds}};
  WriteTextFile(path, j.dump(2) + "\n");
}

namespace {

RunInfo InfoOf(const JsonReader& in, const json& j) {
  in.NoNearMisses(j, "",
                  {"format", "version", "complete", "created_by", "scenario", "seed", "rig",
                   "index", "odometry", "modules", "acquisitions", "images", "acquisition_period_s",
                   "color_filter", "simulation_seconds"});
  if (in.Text(j, "format", "", "") != "sewer3d-run") in.Fail("format", "must be \"sewer3d-run\"");
  if (in.Integer(j, "version", "", 1) != 1) in.Fail("version", "must be 1");
  for (const char* key : {"rig", "index", "odometry"}) {
    const std::string expected = std::string(key) == "rig"     ? "rig.json"
                                 : std::string(key) == "index" ? "acquisitions.csv"
                                                               : "odometry.csv";
    if (in.Text(j, key, "", expected) != expected) in.Fail(key, "must be \"" + expected + "\"");
  }
  RunInfo info;
  info.complete = in.Bool(j, "complete", "", true);
  info.created_by = in.Text(j, "created_by", "", "");
  info.scenario = in.Text(j, "scenario", "", "");
  const auto seed = j.find("seed");
  if (seed != j.end()) {
    if (!seed->is_number_unsigned()) in.Fail("seed", "must be a non-negative integer");
    info.seed = seed->get<std::uint64_t>();
  }
  // The time between two acquisitions of a module; absent or null: not known (held as 0). Nothing
  // downstream relies on it (times come from acquisitions.csv). A period of 0 s is no period.
  const auto period = j.find("acquisition_period_s");
  if (period != j.end() && !period->is_null()) {
    info.acquisition_period_s = in.Number(j, "acquisition_period_s", "");
    if (!(info.acquisition_period_s > 0.0 && info.acquisition_period_s <= kMaxTimeS))
      in.Fail("acquisition_period_s",
              fmt::format("must be above 0 and up to {:g} s (leave it out where not known), got {}",
                          kMaxTimeS, info.acquisition_period_s));
  }
  info.color_filter = in.Text(j, "color_filter", "", "none");
  if (info.color_filter != "none" && info.color_filter != "RGGB")
    in.Fail("color_filter", "must be \"none\" or \"RGGB\", got '" + info.color_filter + "'");
  return info;
}

RunCounts CountsOf(const JsonReader& in, const json& j) {
  RunCounts counts;
  for (auto [key, count] :
       {std::pair{"modules", &counts.modules}, std::pair{"acquisitions", &counts.acquisitions},
        std::pair{"images", &counts.images}}) {
    *count = in.Integer(j, key, "", -1);
    if (j.contains(key) && *count < 0) in.Fail(key, fmt::format("a count, got {}", *count));
  }
  return counts;
}

}  // namespace

RunInfo ReadRunInfo(const fs::path& path) {
  const JsonReader in(path);
  return InfoOf(in, in.ParseObject(ReadTextFile(path)));
}

RunCounts ReadRunCounts(const fs::path& path) {
  const JsonReader in(path);
  return CountsOf(in, in.ParseObject(ReadTextFile(path)));
}

void WriteIndex(const fs::path& path, const std::vector<RunImage>& images) {
  std::string text = std::string(kIndexHeader) + "\n";
  for (const RunImage& e : images) {
    text += fmt::format("{},{},{},{:.6f},{:.3f},{}\n", e.module, e.counter, ImageKindName(e.kind),
                        e.time_s, e.exposure_ms, e.file);
  }
  WriteTextFile(path, text);
}

namespace {

// Each acquisition's images must be taken in order: texture before < pattern < texture after
// (the colour pass interpolates between the two textures to the pattern's instant).
void CheckTripletOrder(const fs::path& path, const std::vector<RunImage>& images,
                       const std::vector<int>& lines) {
  struct Triplet {
    std::array<double, 3> time_s{NAN, NAN, NAN};
    int line = 0;
  };
  std::map<std::pair<int, int>, Triplet> triplets;
  for (std::size_t i = 0; i < images.size(); ++i) {
    Triplet& t = triplets[{images[i].module, images[i].counter}];
    t.time_s[static_cast<int>(images[i].kind)] = images[i].time_s;
    t.line = std::max(t.line, lines[i]);
  }
  for (const auto& [key, t] : triplets) {
    const auto [before, pattern, after] = t.time_s;
    if (before >= pattern || pattern >= after || after <= before) {  // NaN (absent) passes
      throw FileError(path, fmt::format("line {}: module {} counter {}: the images must be taken "
                                        "texture_before < pattern < texture_after, got {} s, {} "
                                        "s, {} s",
                                        t.line, key.first, key.second, before, pattern, after));
    }
  }
}

}  // namespace

std::vector<RunImage> ReadIndex(const fs::path& path) {
  std::vector<RunImage> out;
  std::vector<int> lines;
  std::map<std::string, int> file_lines;
  for (const CsvRow& row : ReadCsv(path, kIndexHeader)) {
    RunImage e;
    ReadImageKey(path, row, e);
    e.exposure_ms = CsvNumber(path, row, 4, "exposure_ms");
    e.file = row.fields[5];
    const auto fail = [&](const std::string& problem) {
      throw FileError(path, fmt::format("line {}: {}", row.line, problem));
    };
    if (e.module < 0) fail(fmt::format("module {} is negative", e.module));
    if (e.counter < 0) fail(fmt::format("counter {} is negative", e.counter));
    if (!(e.exposure_ms >= kMinExposureMs && e.exposure_ms <= kMaxExposureMs)) {
      fail(fmt::format(
          "exposure_ms {} must be {:g}..{:g} ms{}", e.exposure_ms, kMinExposureMs, kMaxExposureMs,
          e.exposure_ms > 0.0 && e.exposure_ms < kMinExposureMs ? " (written in seconds?)" : ""));
    }
    if (std::abs(e.time_s) > kMaxTimeS)
      fail(fmt::format("time_s {} is beyond ±{:g} s", e.time_s, kMaxTimeS));
    if (!InsideRun(e.file)) fail("file '" + e.file + "' must be a path inside the run folder");
    if (const auto [it, fresh] =
            file_lines.emplace(fs::path(e.file).lexically_normal().string(), row.line);
        !fresh) {
      fail(fmt::format("file '{}' is listed on line {} too: each image is one file", e.file,
                       it->second));
    }
    if (!out.empty() && e.time_s < out.back().time_s) {
      fail(fmt::format("time_s {} is before the line above's {}: rows must be sorted by time",
                       e.time_s, out.back().time_s));
    }
    out.push_back(e);
    lines.push_back(row.line);
  }
  CheckTripletOrder(path, out, lines);
  return out;
}

void WriteOdometry(const fs::path& path, const std::vector<OdometryReading>& readings) {
  std::string text = std::string(kOdometryHeader) + "\n";
  for (const auto& r : readings) text += fmt::format("{:.6f},{:.4f}\n", r.time_s, r.distance_mm);
  WriteTextFile(path, text);
}

std::vector<OdometryReading> ReadOdometry(const fs::path& path) {
  std::vector<OdometryReading> out;
  for (const CsvRow& row : ReadCsv(path, kOdometryHeader)) {
    const OdometryReading r{CsvNumber(path, row, 0, "time_s"),
                            CsvNumber(path, row, 1, "distance_mm"), row.line};
    if (std::abs(r.time_s) > kMaxTimeS)
      throw FileError(
          path, fmt::format("line {}: time_s {} is beyond ±{:g} s", row.line, r.time_s, kMaxTimeS));
    if (std::abs(r.distance_mm) > kMaxOdometryMm)
      throw FileError(path, fmt::format("line {}: distance_mm {} is beyond ±{:g} mm", row.line,
                                        r.distance_mm, kMaxOdometryMm));
    if (!out.empty() && r.time_s <= out.back().time_s) {
      throw FileError(path,
                      fmt::format("line {}: time_s {} does not increase", row.line, r.time_s));
    }
    out.push_back(r);
  }
  return out;
}

namespace {

// A rig whose module entries are named after the image folders (m0 .. m5, as the simulator
// and docs/formats.md name them) but in another order than acquisitions.csv's module numbers
// would place every image with another module's calibration and pose: refused.
void CheckFolderMatchesRigName(const fs::path& folder, const std::string& rig_name,
                               const RunImage& image) {
  const auto is_module_name = [](const std::string& name) {
    return name.size() >= 2 && name[0] == 'm' &&
           std::all_of(name.begin() + 1, name.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  const std::string image_folder = fs::path(image.file).parent_path().filename().string();
  if (!is_module_name(rig_name) || !is_module_name(image_folder) || rig_name == image_folder)
    return;
  throw FileError(folder / "rig.json",
                  fmt::format("modules[{0}] is named {1}, but acquisitions.csv lists {2} as "
                              "module {0}'s: the rig's modules are not in the order of the image "
                              "folders",
                              image.module, rig_name, image.file));
}

// The odometry's readings against the images' times: some image must lie in their span, and a
// span a thousand times the images' is a file written in milliseconds.
void CheckOdometrySpan(const fs::path& file, const std::vector<OdometryReading>& readings,
                       const std::vector<RunImage>& images) {
  if (readings.empty()) throw FileError(file, "has no reading");
  if (images.empty()) return;
  const double first = readings.front().time_s, last = readings.back().time_s;
  const bool any_inside = std::any_of(images.begin(), images.end(), [&](const RunImage& i) {
    return i.time_s >= first && i.time_s <= last;
  });
  if (!any_inside) {
    throw FileError(file, fmt::format("the readings cover {:.3f}-{:.3f} s, but no image of "
                                      "acquisitions.csv lies in that time span",
                                      first, last));
  }
  const auto [early, late] =
      std::minmax_element(images.begin(), images.end(),
                          [](const RunImage& a, const RunImage& b) { return a.time_s < b.time_s; });
  const double image_span = late->time_s - early->time_s;
  // Milliseconds read as seconds: a span 1000 times the images', and a 20 Hz counter's readings
  // 50 "s" apart (no counter reads less often than once a second).
  constexpr double kMaxSpanRatio = 200.0;
  const double mean_interval = (last - first) / std::max<double>(1.0, readings.size() - 1.0);
  if (image_span > 0.0 && last - first > kMaxSpanRatio * image_span && mean_interval >= 1.0) {
    throw FileError(
        file, fmt::format("time_s: the readings span {:.3f}-{:.3f} s, {:.0f} times "
                          "the images' {:.3f}-{:.3f} s: time_s must be in seconds "
                          "(milliseconds?)",
                          first, last, (last - first) / image_span, early->time_s, late->time_s));
  }
}

}  // namespace

CaptureRun LoadRun(const fs::path& folder, const LoadRunOptions& options) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw FileError(folder, "is not a run folder");
  if (!fs::exists(folder / "run.json", ec) && fs::exists(folder / "workspace.json", ec))
    throw FileError(folder, "is a processing workspace (workspace.json), not a capture run");
  CaptureRun run;
  run.folder = folder;
  const JsonReader info_reader(folder / "run.json");
  const json info_json = info_reader.ParseObject(ReadTextFile(folder / "run.json"));
  run.info = InfoOf(info_reader, info_json);
  const RunCounts counts = CountsOf(info_reader, info_json);
  if (!run.info.complete && !options.allow_incomplete) {
    throw FileError(folder / "run.json",
                    "the capture stopped part-way (\"complete\": false); images may be missing");
  }
  LoadedRig rig = ReadRig(folder / "rig.json");
  run.rig = std::move(rig.rig);
  run.patterns = std::move(rig.patterns);
  const fs::path index = folder / "acquisitions.csv";
  std::set<std::tuple<int, int, int>> seen;
  for (RunImage& image : ReadIndex(index)) {
    if (image.module >= static_cast<int>(run.rig.modules.size())) {
      // The rig and the images disagree; the rig is what describes the robot.
      throw FileError(folder / "rig.json",
                      fmt::format("modules: {} modules, but acquisitions.csv lists {} of module {}",
                                  run.rig.modules.size(), image.file, image.module));
    }
    CheckFolderMatchesRigName(folder, run.rig.modules[image.module].name, image);
    if (!seen.emplace(image.module, image.counter, static_cast<int>(image.kind)).second) {
      throw FileError(index, fmt::format("module {} counter {} lists two {} images", image.module,
                                         image.counter, ImageKindName(image.kind)));
    }
    if (!fs::is_regular_file(folder / image.file, ec)) {
      if (options.allow_incomplete && !run.info.complete) continue;
      image.missing = true;  // its acquisition fails, the others are processed
    }
    run.images.push_back(std::move(image));
  }
  CheckRunCounts(folder / "run.json", counts, run);
  const double median_gap_s = MedianPatternGap(run.images);
  CheckAcquisitionPeriod(folder / "run.json", run.info.acquisition_period_s, median_gap_s);
  CheckTripletTimes(index, median_gap_s > 0.0 ? median_gap_s : run.info.acquisition_period_s,
                    run.images);
  const std::vector<OdometryReading> readings = ReadOdometry(folder / "odometry.csv");
  OdometryCheck odometry;
  ValidateFileContents(folder / "odometry.csv", [&] { odometry = CheckOdometry(readings); });
  CheckOdometrySpan(folder / "odometry.csv", odometry.kept, run.images);
  run.odometry = std::move(odometry.kept);
  run.odometry_findings = std::move(odometry.findings);
  if (fs::exists(folder / "inclinometer.csv", ec))
    run.inclinometer = ReadInclinometer(folder / "inclinometer.csv");
  return run;
}

}  // namespace sewer3d
