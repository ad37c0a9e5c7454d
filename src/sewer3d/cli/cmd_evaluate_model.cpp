// `sewer3d evaluate model`: the model stage's pipe model against a simulated run's true wall
// (docs/model.md, "Accuracy against the simulator").

#include <fmt/format.h>

#include <filesystem>

#include "sewer3d/cli/evaluate_commands.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/simeval/model_evaluation.hpp"

namespace sewer3d::cli {
namespace {

void PrintRow(const std::string& name, const ErrorFigures& f) {
  if (f.cells == 0) {
    fmt::print("  {:<16} {:>9} (no cell measured)\n", name, 0);
    return;
  }
  fmt::print("  {:<16} {:>9} {:>+9.4f} {:>9.4f} {:>9.4f} {:>9.4f} {:>9.3f}\n", name, f.cells,
             f.mean_mm, f.rms_mm, f.median_abs_mm, f.p95_abs_mm, f.max_abs_mm);
}

}  // namespace

int RunEvaluateModel(const std::string& run_folder, const std::string& workspace,
                     const std::string& out, int stride) {
  ModelEvaluationOptions options;
  options.stride = stride;
  const ModelEvaluation e = EvaluateModel(run_folder, workspace, options);
  const std::filesystem::path folder =
      out.empty() ? std::filesystem::path(workspace) / "evaluation" / "model"
                  : std::filesystem::path(out);
  WriteTextFileAtomically(folder / "evaluation.json", ModelEvaluationToJson(e));
  const std::filesystem::path picture = folder / "error_map.png";
  const std::filesystem::path surface_picture = folder / "error_map_after_axis_offset.png";
  WriteFileAtomically(picture,
                      [&](const std::filesystem::path& t) { WriteImage(t, ModelErrorMap(e)); });
  WriteFileAtomically(surface_picture, [&](const std::filesystem::path& t) {
    WriteImage(t, ModelErrorMap(e, 0.5, 2000, true));
  });
  fmt::print("model surface against the true wall (signed, mm, + outward; every {} cell{}):\n",
             e.stride, e.stride == 1 ? "" : "s along and around");
  fmt::print("  {:<16} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}\n", "cells", "count", "mean", "RMS",
             "median|e|", "P95|e|", "max|e|");
  PrintRow("all", e.all);
  for (const auto& [name, f] : e.by_coverage) PrintRow(name, f);
  for (const auto& [name, f] : e.by_material) PrintRow(name, f);
  PrintRow("away from steps", e.clean);
  const ErrorFigures& a = e.axis_offset;
  fmt::print("{}\n", a.cells == 0 ? "lateral axis offset from the truth: not estimated (no station "
                                    "has measured wall over half its circumference and most of "
                                    "the turn)"
                                  : fmt::format("lateral axis offset from the truth over {} "
                                                "stations: mean {:.3f} mm, P95 {:.3f} mm, max "
                                                "{:.3f} mm; with it removed:",
                                                a.cells, a.mean_mm, a.p95_abs_mm, a.max_abs_mm));
  if (a.cells > 0) {
    PrintRow("all", e.after_axis_offset);
    for (const auto& [name, f] : e.after_axis_offset_by_material) PrintRow(name, f);
    PrintRow("away from steps", e.clean_after_axis_offset);
  }
  const CircumferenceFigures& c = e.circumference;
  fmt::print("{}\n",
             c.sections == 0
                 ? "circumference against the true wall's: not measured (no cross-section "
                   "is measured all around)"
                 : fmt::format("circumference of {} cross-sections against the true "
                               "wall's: mean {:+.3f} mm, mean |d| {:.3f} mm, max |d| "
                               "{:.3f} mm",
                               c.sections, c.mean_diff_mm, c.mean_abs_diff_mm, c.max_abs_diff_mm));
  fmt::print("wrote {}, {} and {}\n", (folder / "evaluation.json").string(), picture.string(),
             surface_picture.string());
  return 0;
}

}  // namespace sewer3d::cli
