#pragma once
/// \file
/// How good the RGB-D stage's colour is, measured on a simulated run against its truth
/// (docs/texture.md): per wall material, the mean CIEDE2000 between the texture and the true
/// albedo after one global gain per channel (exposure and white balance, which no method
/// without a target can know), before correction (texture_before as captured) and after (the
/// stage's colour image); the colour-to-geometry misregistration (px) of the stage's colour
/// image and of the naive one (texture_before as is) against the albedo seen at the pattern
/// instant; and the colour difference of the same wall point seen by two neighbouring modules.
/// Reads the run's truth/ and the workspace; the stage itself never reads truth/.

#include <filesystem>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

struct RgbdEvaluationOptions {
  int acquisitions_per_module = 6;  ///< complete acquisitions used, evenly spread over the run
  int stride_px = 6;                ///< colour statistics on every stride-th pixel and row
  /// Colours are compared after a box mean of this side (px; 1: per pixel), so that the
  /// figure is about colour rather than the last pixel of sharpness and registration.
  int colour_smoothing_px = 5;
  int crop_px = 384;  ///< side of the window of the misregistration measurement
  /// Colours are compared at the seams after a box mean of this side (px): the seam test is
  /// about colour, not about the fine texture's registration.
  int seam_smoothing_px = 7;
  void Check() const;
};

/// One material's figures (mean over its sampled pixels or acquisitions).
struct MaterialColourFigures {
  long long pixels = 0;
  int acquisitions = 0;
  double delta_e_before = 0.0;  ///< mean ΔE00, texture_before as captured vs its albedo truth
  double delta_e_after = 0.0;   ///< mean ΔE00, the stage's colour vs the pattern instant's truth
  /// The same with one gain per module instead of one for the run (diagnostic: what is left
  /// when the modules' levels are taken as right).
  double delta_e_after_module_gains = 0.0;
  /// Medians over the acquisitions where the phase correlation's peak means something (NaN
  /// where none: a featureless wall); `acquisitions` counts the mapped ones.
  double misregistration_naive_px = 0.0;
  double misregistration_mapped_px = 0.0;
};

struct SeamFigures {
  int pairs = 0;                ///< neighbouring (module, module + 1) acquisitions of one counter
  long long points = 0;         ///< wall points seen by both
  double delta_e_before = 0.0;  ///< mean ΔE00 between the two modules' captured textures
  double delta_e_after = 0.0;   ///< mean ΔE00 between the two modules' colour images
};

struct RgbdEvaluation {
  std::map<std::string, MaterialColourFigures> materials;  ///< by material name
  SeamFigures seams;
  cv::Vec3d gains_before_bgr{1, 1, 1}, gains_after_bgr{1, 1, 1};  ///< the global gains
  int acquisitions = 0;
  /// Crops (captured | stage colour | true albedo, sRGB) of one acquisition per material, for
  /// people to look at.
  cv::Mat3b montage;
};

/// Evaluates the RGB-D stage's outputs in `workspace` (WS) for the simulated `run`. Throws
/// FileError when truth/ or the workspace lacks what is needed (e.g. albedo truth).
RgbdEvaluation EvaluateRgbd(const CaptureRun& run, const std::filesystem::path& workspace,
                            const RgbdEvaluationOptions& options);

/// The evaluation as JSON text (keys sorted).
std::string RgbdEvaluationToJson(const RgbdEvaluation& evaluation);

}  // namespace sewer3d
