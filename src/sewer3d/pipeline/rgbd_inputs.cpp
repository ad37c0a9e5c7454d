#include "sewer3d/pipeline/rgbd_inputs.hpp"

#include <fmt/core.h>

#include <nlohmann/json.hpp>
#include <set>
#include <system_error>
#include <unordered_map>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_stamp.hpp"
#include "sewer3d/io/file_stamp_json.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/pipeline/acquisition_images.hpp"

namespace sewer3d {
namespace {

using json = nlohmann::json;

// The "inputs" of an acquisition's geometry report; an empty object when it has none (written
// before stamps existed) or cannot be read.
json RecordedStamps(const std::filesystem::path& geometry_report) {
  try {
    const json j = json::parse(ReadTextFile(geometry_report));
    if (j.contains("inputs") && j["inputs"].is_object()) return j["inputs"];
  } catch (const std::exception&) {  // a damaged report is redone by the pass that reads it
  }
  return json::object();
}

// The first image of `recorded` the run no longer holds as stamped; empty when all match.
std::string ChangedImage(const CaptureRun& run, const json& recorded) {
  for (const auto& [kind, entry] : recorded.items()) {
    try {
      const std::filesystem::path file = run.folder / entry.at("file").get<std::string>();
      if (!StillStamped(StampFromJson(entry), file)) return file.string();
    } catch (const std::exception&) {
      return kind;  // a stamp that cannot be read is not trusted
    }
  }
  return {};
}

// The acquisitions (module, counter) the last finished rgbd run left out as failed, by its
// report; none when there is no readable report.
std::set<std::pair<int, int>> LeftOut(const std::filesystem::path& stage_report) {
  std::set<std::pair<int, int>> left_out;
  try {
    const json report = json::parse(ReadTextFile(stage_report));  // outlives the loop
    for (const json& f : report.at("failures"))
      left_out.emplace(f.at("module").get<int>(), f.at("counter").get<int>());
  } catch (const std::exception&) {  // missing or damaged: nothing counts as left out
  }
  return left_out;
}

// Why an acquisition the geometry pass finished must be redone, in words ("RUN/…png changed",
// "WS/rgbd/m0/000001_depth.tiff removed"); empty when it stands.
std::string WhyRedo(const CaptureRun& run, const RgbdFiles& files) {
  const std::string changed = ChangedImage(run, RecordedStamps(files.geometry));
  if (!changed.empty()) return changed + " changed";
  for (const std::filesystem::path& output : {files.depth, files.cloud})
    if (!IsRegularFile(output)) return output.string() + " removed";
  return {};
}

// A finished acquisition whose colour image was removed since: its colour pass is redone.
bool ColourLost(const RgbdFiles& files) {
  return IsRegularFile(files.report) && !IsRegularFile(files.color);
}

}  // namespace

json InputStamps(const CaptureRun& run, const Acquisition& a) {
  json stamps = json::object();
  for (const ImageKind kind : kImageKinds) {
    if (a.Image(kind) < 0 || run.images[a.Image(kind)].missing) continue;
    const RunImage& image = run.images[a.Image(kind)];
    json stamp = StampToJson(StampFile(run.folder / image.file));
    stamp["file"] = image.file;
    stamps[ImageKindName(kind)] = stamp;
  }
  return stamps;
}

std::vector<std::string> ForgetChangedAcquisitions(const CaptureRun& run,
                                                   const std::vector<Acquisition>& acquisitions,
                                                   const std::filesystem::path& rgbd_folder) {
  std::vector<std::string> lines;
  for (const Acquisition& a : acquisitions) {
    const RgbdFiles files = RgbdAcquisitionFiles(rgbd_folder, a.module, a.counter);
    if (!RgbdGeometryDone(files)) continue;
    std::string changed = WhyRedo(run, files);
    // A colour image removed is ColourLost's (below: only the colour is redone).
    if (const std::string damaged = RgbdDamagedFile(files);
        changed.empty() && !damaged.empty() && !ColourLost(files))
      changed = damaged + " cut short or replaced";
    if (changed.empty() && ColourLost(files)) {
      std::error_code ec;
      std::filesystem::remove(files.report, ec);
      lines.push_back(
          fmt::format("m{} counter {}: {} removed since an earlier run processed it: "
                      "its colour is redone",
                      a.module, a.counter, files.color.string()));
    }
    if (changed.empty()) continue;
    std::error_code ec;
    std::filesystem::remove(files.report, ec);
    std::filesystem::remove(files.geometry, ec);
    lines.push_back(
        fmt::format("m{} counter {}: {} since an earlier run processed it: "
                    "the acquisition is redone",
                    a.module, a.counter, changed));
  }
  return lines;
}

bool RgbdUpToDate(const CaptureRun& run, const std::filesystem::path& rgbd_folder) {
  for (const Acquisition& a : GroupAcquisitions(run.images)) {
    const RgbdFiles files = RgbdAcquisitionFiles(rgbd_folder, a.module, a.counter);
    if (!RgbdGeometryDone(files) || !RgbdAcquisitionDone(files)) return false;
    if (!WhyRedo(run, files).empty() || ColourLost(files)) return false;
  }
  return true;
}

std::string RgbdBehind(const CaptureRun& run, const Workspace& workspace) {
  const auto rgbd = workspace.record().stages.find("rgbd");
  if (rgbd != workspace.record().stages.end() && rgbd->second.stale) {
    return workspace.RecordFile().string() +
           ": the rgbd stage is stale (the run's rig.json, a pattern matrix or acquisitions.csv "
           "changed since it ran)";
  }
  const std::filesystem::path folder = workspace.StageFolder("rgbd");
  const std::set<std::pair<int, int>> left_out = LeftOut(folder / "report.json");
  for (const Acquisition& a : GroupAcquisitions(run.images)) {
    const RgbdFiles files = RgbdAcquisitionFiles(folder, a.module, a.counter);
    const bool current = RgbdGeometryDone(files) && RgbdAcquisitionDone(files) &&
                         !ColourLost(files) && WhyRedo(run, files).empty();
    if (current || left_out.count({a.module, a.counter}) > 0) continue;
    return fmt::format(
        "{}: does not hold m{} counter {} as the run has it now (rgbd unfinished, or images "
        "added or replaced since)",
        folder.string(), a.module, a.counter);
  }
  return {};
}

std::vector<std::string> PatternMatrixWarnings(const CaptureRun& run,
                                               const std::vector<PatternConstraints>& inferred) {
  const PatternConstraints wanted;
  std::vector<std::string> lines;
  for (size_t k = 0; k < inferred.size() && k < run.rig.modules.size(); ++k) {
    const PatternConstraints& c = inferred[k];
    std::string problem;
    if (!c.isolated) problem = "spots touch (8-adjacent)";
    if (c.min_hamming < wanted.min_hamming) {
      problem += fmt::format("{}windows differ in as few as {} spots (at least {} wanted)",
                             problem.empty() ? "" : ", ", c.min_hamming, wanted.min_hamming);
    }
    if (c.min_weight < wanted.min_weight) {
      problem += fmt::format("{}windows hold as few as {} spots (at least {} wanted)",
                             problem.empty() ? "" : ", ", c.min_weight, wanted.min_weight);
    }
    if (problem.empty()) continue;
    lines.push_back(fmt::format(
        "{}: modules[{}]: the pattern matrix {} breaks the pattern constraints: {}; its spots "
        "decode badly or not at all (sewer3d describe checks a module)",
        (run.folder / "rig.json").string(), k, run.rig.modules[k].module.pattern.matrix_path,
        problem));
  }
  return lines;
}

std::vector<std::string> RepeatedImageWarnings(const CaptureRun& run,
                                               const std::vector<Acquisition>& acquisitions,
                                               const std::filesystem::path& rgbd_folder) {
  std::vector<std::string> lines;
  std::unordered_map<std::string, const Acquisition*> first_with;  // pattern hash → acquisition
  const Acquisition* previous = nullptr;
  for (const Acquisition& a : acquisitions) {  // ordered by (module, counter)
    const json stamps =
        RecordedStamps(RgbdAcquisitionFiles(rgbd_folder, a.module, a.counter).geometry);
    const std::string hash =
        stamps.contains("pattern") ? stamps["pattern"].value("hash", std::string()) : "";
    const Acquisition* before = previous;
    previous = &a;
    if (hash.empty()) continue;
    const auto [seen, is_new] = first_with.try_emplace(hash, &a);
    if (is_new) continue;
    const Acquisition& other = *seen->second;
    const std::string file = AcquisitionImageFile(run, a, ImageKind::kPattern).string();
    if (other.module == a.module && before != nullptr && before->module == a.module &&
        before->counter == other.counter) {
      lines.push_back(fmt::format(
          "{}: the pattern image of m{} counter {} is byte for byte that of counter {}: a camera "
          "that delivers the same frame again? The odometry places the two at different stations",
          file, a.module, a.counter, other.counter));
    } else {
      lines.push_back(fmt::format(
          "{}: the pattern image of m{} counter {} is byte for byte that of m{} counter {}: an "
          "image copied or filed under the wrong module or counter?",
          file, a.module, a.counter, other.module, other.counter));
    }
  }
  return lines;
}

std::string ExposureProblem(const cv::Mat3f& linear) {
  if (linear.empty()) return {};
  constexpr float kSaturated = 254.5F / 255.0F, kBlack = 1.5F / 255.0F;
  long long saturated = 0, black = 0;
  for (int r = 0; r < linear.rows; ++r) {
    for (const cv::Vec3f& p : cv::Mat_<cv::Vec3f>(linear.row(r))) {
      const float high = std::max({p[0], p[1], p[2]});
      saturated += high >= kSaturated;
      black += high <= kBlack;
    }
  }
  const double total = static_cast<double>(linear.total());
  if (saturated > total / 2) {
    return fmt::format(
        "{:.0f} % of the pixels are saturated (blown out): the texture there has "
        "no colour and no detail",
        100.0 * saturated / total);
  }
  if (black > total / 2) {
    return fmt::format("{:.0f} % of the pixels are black: no light, or a lens cap?",
                       100.0 * black / total);
  }
  return {};
}

}  // namespace sewer3d
