// `sewer3d evaluate rgbd`: the RGB-D stage's colour against a simulated run's truth
// (docs/texture.md).

#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "sewer3d/cli/evaluate_commands.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/simeval/rgbd_evaluation.hpp"

namespace sewer3d::cli {

int RunEvaluateRgbd(const std::string& run_folder, const std::string& workspace,
                    const std::string& out, int smoothing_px) {
  const CaptureRun run = LoadRun(run_folder);
  const std::filesystem::path rgbd = std::filesystem::path(workspace) / "rgbd";
  if (!std::filesystem::is_directory(rgbd))
    throw FileError(rgbd, "no such folder: run `sewer3d rgbd` (or `process`) first");
  RgbdEvaluationOptions options;
  options.colour_smoothing_px = smoothing_px;
  const RgbdEvaluation e = EvaluateRgbd(run, workspace, options);
  if (e.acquisitions == 0) {
    fmt::print(stderr, "sewer3d: error: {}: no acquisition of {} has RGB-D results to evaluate\n",
               rgbd.string(), run_folder);
    return 1;
  }
  const std::filesystem::path folder =
      out.empty() ? std::filesystem::path(workspace) / "evaluation" / "rgbd"
                  : std::filesystem::path(out);
  WriteTextFileAtomically(folder / "evaluation.json", RgbdEvaluationToJson(e));
  if (!e.montage.empty()) WriteImage(folder / "colour_montage.png", e.montage);
  fmt::print(
      "rgbd colour over {} acquisitions (mean CIEDE2000 after one global gain; "
      "misregistration: median px)\n",
      e.acquisitions);
  fmt::print("{:<16} {:>10} {:>10} {:>14} {:>10} {:>10}\n", "material", "dE before", "dE after",
             "(gain/module)", "naive px", "mapped px");
  for (const auto& [name, m] : e.materials) {
    // Misregistration is measured on acquisitions where the material covers most of the view
    // and the wall has enough texture for a phase correlation.
    const auto px = [](double v) {
      return std::isfinite(v) ? fmt::format("{:.2f}", v) : std::string("-");
    };
    fmt::print("{:<16} {:>10.2f} {:>10.2f} {:>14.2f} {:>10} {:>10}\n", name, m.delta_e_before,
               m.delta_e_after, m.delta_e_after_module_gains, px(m.misregistration_naive_px),
               px(m.misregistration_mapped_px));
  }
  fmt::print("seams: {} neighbour pairs, {} wall points: dE before {:.2f}, after {:.2f}\n",
             e.seams.pairs, e.seams.points, e.seams.delta_e_before, e.seams.delta_e_after);
  fmt::print("wrote {}\n", (folder / "evaluation.json").string());
  return 0;
}

}  // namespace sewer3d::cli
