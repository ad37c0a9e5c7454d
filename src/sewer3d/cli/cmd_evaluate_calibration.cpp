// `sewer3d evaluate calibration`: a module calibrated from simulated captures against the module
// they were rendered with and the nearest module a file can hold for their lenses
// (docs/calibration.md; simeval/calibration_evaluation.hpp).

#include <fmt/core.h>

#include <filesystem>

#include "sewer3d/cli/evaluate_commands.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/calibration_io.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/simeval/calibration_evaluation.hpp"
#include "sewer3d/simio/truth_io.hpp"

namespace sewer3d::cli {

int RunEvaluateCalibration(const std::string& captures, const std::string& module,
                           const std::string& out) {
  const std::filesystem::path truth_file = std::filesystem::path(captures) / "truth" / "poses.json";
  if (!std::filesystem::is_regular_file(truth_file)) {
    throw FileError(captures,
                    "has no truth/poses.json: not captures of `sewer3d simulate calibration`, "
                    "whose truth the module is judged against");
  }
  const CalibrationTruth truth = ReadCalibrationTruth(truth_file);
  const LoadedModule true_module = LoadModule(truth_file.parent_path() / "module.json");
  const LoadedModule calibrated = LoadModule(module);
  const auto sigma = ModuleCalibrationSigma(calibrated.module, module);
  if (!sigma) {
    throw FileError(module,
                    "has no 'calibration' member with the standard deviations (a module "
                    "written by `sewer3d calibrate module` carries one)");
  }
  if (calibrated.module.camera.width != true_module.module.camera.width ||
      calibrated.module.camera.height != true_module.module.camera.height) {
    throw FileError(module,
                    fmt::format("is a {}x{} camera's module; the captures' is {}x{}",
                                calibrated.module.camera.width, calibrated.module.camera.height,
                                true_module.module.camera.width, true_module.module.camera.height));
  }
  const SpotErrors lenses = ModuleOwnErrors(*RealismProfile(truth.realism));
  const ModuleCalibrationResult nearest =
      NearestFileModule(true_module.module, lenses, truth.board, truth.camera_from_board);
  const CalibrationEvaluation e =
      EvaluateCalibration(true_module.module, nearest, calibrated.module, *sigma);
  fmt::print(
      "calibration of {} against the module of {} (realism {}); the nearest module a file can "
      "hold for these lenses fits the exact corners to RMS {:.4f} px (camera), {:.4f} px "
      "(projector)\n",
      module, captures, truth.realism, e.nearest_camera_rms_px, e.nearest_projector_rms_px);
  fmt::print("  {:<18} {:>12} {:>12} {:>12} {:>9} {:>9} {:>11}\n", "parameter", "true", "nearest",
             "calibrated", "sigma", "error", "to nearest");
  for (const CalibrationParameter& p : e.parameters) {
    fmt::print("  {:<18} {:>12.4f} {:>12.4f} {:>12.4f} {:>9.4f} {:>+8.2f}σ {:>+10.2f}σ\n",
               p.name + " (" + p.unit + ")", p.truth, p.nearest, p.calibrated, p.sigma,
               p.error_sigmas, p.error_to_nearest_sigmas);
  }
  fmt::print("within 2 σ: {} of {} parameters of the true module, {} of the nearest file module\n",
             e.within_2_sigma, e.parameters.size(), e.within_2_sigma_of_nearest);
  if (!out.empty()) {
    WriteTextFileAtomically(out, CalibrationEvaluationToJson(e, truth.realism));
    fmt::print("wrote {}\n", out);
  }
  return 0;
}

}  // namespace sewer3d::cli
