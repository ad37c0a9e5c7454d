// `sewer3d evaluate inspection`: the inspection's observations and profile against a simulated
// run's true pipe (docs/inspection.md, "Accuracy").

#include <fmt/core.h>

#include <cmath>
#include <filesystem>

#include "sewer3d/cli/evaluate_commands.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/simeval/inspection_evaluation.hpp"

namespace sewer3d::cli {
namespace {

void PrintItem(const TrueItemMatch& m) {
  if (!m.inspected) {
    fmt::print(
        "  {:<4} {:<4} at {:8.1f} mm {:5.2f} h: not inspected (outside the searched stations)\n",
        m.truth_id, m.code, m.station_mm, m.clock_h);
    return;
  }
  if (m.observation_id.empty()) {
    fmt::print("  {:<4} {:<4} at {:8.1f} mm {:5.2f} h: NOT FOUND\n", m.truth_id, m.code,
               m.station_mm, m.clock_h);
    return;
  }
  std::string values;
  for (const TrueItemMatch::Value& v : m.values) {
    values += std::isfinite(v.measured)
                  ? fmt::format("; {} {:.2f} (true {:.2f}, {:+.2f})", v.name, v.measured, v.truth,
                                v.measured - v.truth)
                  : fmt::format("; {} not measured (true {:.2f})", v.name, v.truth);
  }
  fmt::print("  {:<4} {:<4} = {:<4} station {:+.1f} mm, clock {:+.2f} h{}\n", m.truth_id, m.code,
             m.observation_id, m.station_error_mm, m.clock_error_h, values);
}

}  // namespace

int RunEvaluateInspection(const std::string& run_folder, const std::string& workspace,
                          double local_alignment_mm, const std::string& out) {
  const InspectionFilesEvaluation e = EvaluateInspection(run_folder, workspace, local_alignment_mm);
  const std::filesystem::path folder =
      out.empty() ? std::filesystem::path(workspace) / "evaluation" / "inspection"
                  : std::filesystem::path(out);
  WriteTextFileAtomically(folder / "evaluation.json", InspectionEvaluationToJson(e));
  const InspectionEvaluation& o = e.observations;
  fmt::print(
      "observations against the true pipe{}: {} of {} inspected true items found, {} "
      "invented{}\n",
      local_alignment_mm > 0.0
          ? fmt::format(" (aligned by the cameras within ±{:g} mm of each)", local_alignment_mm)
          : "",
      o.found, o.inspected, o.invented.size(), o.invented.empty() ? "" : ":");
  for (const std::string& id : o.invented) fmt::print("  invented: {}\n", id);
  for (const TrueItemMatch& m : o.items) PrintItem(m);
  const ProfileEvaluation& p = e.profile;
  if (p.clean_rows == 0) {
    fmt::print(
        "profile against the true rings: not measured (no clean station: none measured all round "
        "at least 50 mm from every joint and feature)\n");
  } else {
    fmt::print(
        "profile against the true rings over {} clean stations: circumference |error| median "
        "{:.3f} %, max {:.3f} %; ovality (EN) |error| median {:.3f}, max {:.3f} points; ASTM max "
        "{:.3f} points\n",
        p.clean_rows, p.circumference_pct.median, p.circumference_pct.max, p.ovality_en_pct.median,
        p.ovality_en_pct.max, p.ovality_astm_pct.max);
  }
  fmt::print("wrote {}\n", (folder / "evaluation.json").string());
  return 0;
}

}  // namespace sewer3d::cli
