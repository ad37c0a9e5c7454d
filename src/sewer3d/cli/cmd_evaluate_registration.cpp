// `sewer3d evaluate registration`: the registration stage's poses against a simulated run's
// truth (docs/registration.md).

#include <fmt/core.h>

#include <filesystem>

#include "sewer3d/cli/evaluate_commands.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/simeval/registration_evaluation.hpp"

namespace sewer3d::cli {

int RunEvaluateRegistration(const std::string& run_folder, const std::string& workspace,
                            const std::string& out) {
  const RegistrationEvaluation e = EvaluateRegistration(run_folder, workspace);
  const std::filesystem::path folder =
      out.empty() ? std::filesystem::path(workspace) / "evaluation" / "registration"
                  : std::filesystem::path(out);
  WriteTextFileAtomically(folder / "evaluation.json", RegistrationEvaluationToJson(e));
  WriteTextFileAtomically(folder / "edges.csv", EdgeErrorsToCsv(e.edge_errors));
  WriteTextFileAtomically(folder / "nodes.csv", NodeErrorsToCsv(e.node_errors));
  WriteTextFileAtomically(folder / "trajectory_error.svg", TrajectoryErrorSvg(e.node_errors));
  fmt::print(
      "absolute trajectory error of {} camera centres (one rigid alignment): RMS {:.3f} mm, "
      "max {:.3f} mm\n",
      e.ate.nodes, e.ate.rms_mm, e.ate.max_mm);
  for (const auto& [name, f] : e.ate_by_material)
    fmt::print("  {:<16} {:>4} nodes  RMS {:.3f} mm  max {:.3f} mm\n", name, f.nodes, f.rms_mm,
               f.max_mm);
  fmt::print("accepted edges against the true relative poses:\n");
  fmt::print("  {:<18} {:>6} {:>12} {:>12} {:>12} {:>10} {:>10}\n", "type", "edges", "median mm",
             "median deg", "at wall mm", "mean NEES", "med NEES");
  const auto row = [](const std::string& label, const EdgeErrorFigures& f) {
    fmt::print("  {:<18} {:>6} {:>12.4f} {:>12.4f} {:>12.4f} {:>10.2f} {:>10.2f}\n", label,
               f.accepted, f.median_translation_mm, f.median_rotation_deg, f.median_wall_mm,
               f.mean_nees, f.median_nees);
  };
  for (const auto& [type, f] : e.edges) row(type, f);
  for (const auto& [key, f] : e.edges_by_kind) row(key, f);
  fmt::print(
      "wrote {}, edges.csv (every accepted edge), nodes.csv (every camera) and "
      "trajectory_error.svg\n",
      (folder / "evaluation.json").string());
  return 0;
}

}  // namespace sewer3d::cli
