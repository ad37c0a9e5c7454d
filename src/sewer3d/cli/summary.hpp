#pragma once
/// \file
/// Human-readable summary of a module and its pattern, shared by `module` and `describe`.

#include <string>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/pattern/binary_array.hpp"

namespace sewer3d::cli {

/// Prints geometry (fields of view, baseline, stereo angle), the disparity range over the
/// working range and the pattern's verified properties. Returns what makes the module unusable
/// (the pattern does not span the disparity range, or violates its constraints), or "".
std::string PrintModuleSummary(const ModuleDescription& module, const BinaryArray& pattern);

/// The disparity error the depth precision is quoted for (camera px): spot centres are
/// found to about this.
inline constexpr double kDisparityErrorPx = 0.1;

/// Depth error (mm) at distance `z_mm` for kDisparityErrorPx: z² σ / (f b), b the baseline
/// across the view.
double DepthErrorMm(const ModuleDescription& module, double z_mm);

/// "" when the depth error at the far end of the working range is at most 1 mm, else why the
/// module would measure the wall too coarsely (a 2.6 mm baseline at 648 px: ±4.5 mm).
std::string DepthPrecisionProblem(const ModuleDescription& module);

/// "" when a window of `window` x `window` pattern elements fits on the projector at the
/// module's pitch (the decoder reads such windows), else why not.
std::string WindowFitProblem(const ModuleDescription& module, int window);

/// Why the camera images the pattern's spots too small to decode (under 1.5 px across, or a
/// pitch under 3 px: the simulator's plane decodes under half its spots there); empty when it
/// resolves them.
std::string SpotSizeProblem(const ModuleDescription& module);

}  // namespace sewer3d::cli
