#include "sewer3d/pipeline/register_warnings.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <map>

#include "sewer3d/core/union_find.hpp"

namespace sewer3d {
namespace {

constexpr double kMaxCarrierSpeedMmS = 2000.0;

}  // namespace

std::vector<std::string> OdometryWarnings(const CaptureRun& run,
                                          const std::vector<AcquisitionNode>& nodes) {
  const std::string file = (run.folder / "odometry.csv").string();
  const OdometryFindings& f = run.odometry_findings;
  std::vector<std::string> lines;
  for (const OdometryReversal& r : f.reversals) {
    lines.push_back(fmt::format(
        "{}: line{} {}: the distance goes back from {:.1f} mm to {:.1f} mm (more than {} mm): "
        "{} reading{} dropped, a cable counter only counts forward",
        file, r.first_line == r.last_line ? "" : "s",
        r.first_line == r.last_line ? std::to_string(r.first_line)
                                    : fmt::format("{}-{}", r.first_line, r.last_line),
        r.before_mm, r.lowest_mm, f.options.reversal_tolerance_mm, r.readings,
        r.readings == 1 ? "" : "s"));
  }
  if (!run.odometry.empty()) {
    const double first = run.odometry.front().time_s, last = run.odometry.back().time_s;
    const auto outside = std::count_if(nodes.begin(), nodes.end(), [&](const AcquisitionNode& n) {
      return n.time_s < first || n.time_s > last;
    });
    if (outside > 0) {
      lines.push_back(fmt::format(
          "{}: the readings cover {:.3f}-{:.3f} s, but {} of {} acquisitions lie outside that "
          "span: they got the nearest reading's distance, so the odometry does not place them",
          file, first, last, outside, nodes.size()));
    }
    const auto [low, high] =
        std::minmax_element(run.odometry.begin(), run.odometry.end(),
                            [](const OdometryReading& a, const OdometryReading& b) {
                              return a.distance_mm < b.distance_mm;
                            });
    // A crawler moves at most a few hundred mm/s; a jump far faster is a counter glitch or a
    // reading in other units, and places the acquisitions around it wrongly.
    for (std::size_t i = 1; i < run.odometry.size(); ++i) {
      const OdometryReading &a = run.odometry[i - 1], &b = run.odometry[i];
      const double speed = (b.distance_mm - a.distance_mm) / (b.time_s - a.time_s);
      if (speed > kMaxCarrierSpeedMmS) {
        lines.push_back(fmt::format(
            "{}: lines {}-{}: the distance jumps {:.1f} mm in {:.3f} s ({:.0f} mm/s, more than a "
            "carrier's {:.0f} mm/s): a counter glitch or other units; acquisitions around it are "
            "placed by it",
            file, a.line, b.line, b.distance_mm - a.distance_mm, b.time_s - a.time_s, speed,
            kMaxCarrierSpeedMmS));
        break;  // the first one: the cause is the same for the others
      }
    }
    if (run.odometry.size() >= 2 && high->distance_mm - low->distance_mm < 1.0) {
      const double span = high->distance_mm - low->distance_mm;
      lines.push_back(fmt::format(
          "{}: the distance {} in all {} readings: the carrier did not move, the counter is "
          "stuck{}, so the odometry separates no acquisitions",
          file,
          span > 0.0 ? fmt::format("spans only {:.3g} mm", span)
                     : fmt::format("stays at {:.1f} mm", low->distance_mm),
          run.odometry.size(), span > 0.0 ? " or distance_mm is in metres" : ""));
    }
  }
  for (const OdometryGap& g : f.gaps) {
    std::string inside;
    double sigma = 0.0;
    int count = 0;
    for (const AcquisitionNode& n : nodes) {
      if (n.time_s <= g.from_s || n.time_s >= g.to_s) continue;
      if (count++ < 6)
        inside += fmt::format("{}m{} counter {}", inside.empty() ? "" : ", ", n.module, n.counter);
      sigma = std::max(sigma, n.distance_sigma_mm);
    }
    if (count > 6) inside += fmt::format(" and {} more", count - 6);
    lines.push_back(fmt::format(
        "{}: no reading between line {} ({:.3f} s) and line {} ({:.3f} s), {:.2f} s (more than "
        "{} s): {}",
        file, g.from_line, g.from_s, g.to_line, g.to_s, g.to_s - g.from_s, f.options.max_gap_s,
        count == 0 ? std::string("no acquisition in it")
                   : fmt::format("{} acquisition{} placed by interpolation with σ up to {:.1f} mm "
                                 "along the pipe ({})",
                                 count, count == 1 ? "" : "s", sigma, inside)));
  }
  return lines;
}

std::vector<std::string> RigWarnings(const CaptureRun& run,
                                     const std::vector<ModulePairAgreement>& pairs) {
  const std::string file = (run.folder / "rig.json").string();
  std::map<int, int> flagged;  // module → pairs that disagree
  for (const ModulePairAgreement& p : pairs) {
    if (!Disagrees(p)) continue;
    ++flagged[p.module_a];
    ++flagged[p.module_b];
  }
  std::vector<std::string> lines;
  for (const ModulePairAgreement& p : pairs) {
    if (!Disagrees(p)) continue;
    std::string likely = "one of the two";
    if (flagged[p.module_a] > 1 && flagged[p.module_b] == 1)
      likely = fmt::format("m{}", p.module_a);
    if (flagged[p.module_b] > 1 && flagged[p.module_a] == 1)
      likely = fmt::format("m{}", p.module_b);
    lines.push_back(fmt::format(
        "{}: modules m{} and m{}: the gate rejected {} of their {} registrations, which put the "
        "cameras {:.1f} mm (median) from where the rig has them: the carrier_from_camera of {} "
        "is wrong (units? clock position?), their image folders are swapped, or its times in "
        "acquisitions.csv are off (a module clock); the model there follows the rig, not the "
        "images",
        file, p.module_a, p.module_b, p.rejected, p.edges, p.median_rejected_offset_mm, likely));
  }
  return lines;
}

std::string GraphWarning(int nodes, const std::vector<RegistrationEdge>& edges) {
  UnionFind sets(nodes);
  for (const RegistrationEdge& e : edges) sets.Join(e.a, e.b);
  std::map<int, int> parts;
  for (int i = 0; i < nodes; ++i) ++parts[sets.Root(i)];
  if (parts.size() <= 1) return {};
  int largest = 0;
  for (const auto& [r, n] : parts) largest = std::max(largest, n);
  return fmt::format(
      "the edges leave the pose graph in {} unconnected parts (the largest {} of {} "
      "acquisitions): their poses relative to each other are the odometry's and rig's initial "
      "guess, not measured (give --edges more kinds, e.g. the default)",
      parts.size(), largest, nodes);
}

std::string CarrierWarning(const CaptureRun& run, const CarrierOffsetEstimate& walls) {
  if (!walls.valid || walls.diameter_mm > run.rig.carrier_diameter_mm) return {};
  return fmt::format(
      "{}: carrier.diameter_mm is {:g} mm, but the walls its modules see at the first instant "
      "are a pipe of {:.0f} mm: the carrier cannot be wider than the pipe (units?)",
      (run.folder / "rig.json").string(), run.rig.carrier_diameter_mm, walls.diameter_mm);
}

std::string AlongWarning(const CaptureRun& run, const ModulePairAgreement& along) {
  if (!Disagrees(along)) return {};
  return fmt::format(
      "{}: the gate rejected {} of the {} registrations along the pipe (between acquisitions of "
      "one module), which put the cameras {:.1f} mm (median) from where the odometry has them: "
      "is distance_mm in millimetres (not inches, metres or another scale)? The poses follow the "
      "odometry, not the images",
      (run.folder / "odometry.csv").string(), along.rejected, along.edges,
      along.median_rejected_offset_mm);
}

std::string OdometryRejectedWarning(const CaptureRun& run, const EdgeTypeStatistics& odometry) {
  const int rejected = odometry.edges - odometry.accepted;
  if (odometry.edges < 2 || 2 * rejected < odometry.edges) return {};
  return fmt::format(
      "{}: the gate rejected {} of the {} odometry edges: the images put the acquisitions "
      "elsewhere than the counter's distances say; is distance_mm in millimetres and the "
      "counter's scale right (not inches, metres, a drum or wheel calibration), or did the cable "
      "slip over a stretch of the run? The poses follow the images",
      (run.folder / "odometry.csv").string(), rejected, odometry.edges);
}

std::string OdometryFitWarning(const CaptureRun& run, const EdgeTypeStatistics& odometry) {
  constexpr double kMaxMedianChi2 = 100.0;
  if (odometry.accepted < 2 || !(odometry.median_chi2 > kMaxMedianChi2)) return {};
  return fmt::format(
      "{}: the odometry disagrees with the registrations: its edges' median χ² is {:.3g} at the "
      "solution (about 6 when they agree), their residual {:.1f} mm RMS: is the counter's scale "
      "right (drum or wheel calibration, units)? The poses are a compromise between the two",
      (run.folder / "odometry.csv").string(), odometry.median_chi2, odometry.rms_translation_mm);
}

}  // namespace sewer3d
