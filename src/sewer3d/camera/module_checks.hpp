#pragma once
/// \file
/// Whether the decoder can use a module: depth precision over the working distances, spots the
/// camera resolves, a pattern window that fits on the projector, a pattern that spans the
/// disparity. `module` refuses to write such a module, `describe` calls it unusable.

#include <optional>
#include <string>

#include "sewer3d/camera/module.hpp"

namespace sewer3d {

/// The disparity error the depth precision is quoted for (camera px): spot centres are found to
/// about this.
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

/// Share of the camera's view (a grid of pixels) that the projector lights on a wall facing the
/// camera at `z_mm` (its rays meeting the plane z = z_mm inside the projector image).
double LitShare(const ModuleDescription& module, double z_mm);

/// "" when the projector lights at least a third of the camera's view somewhere in the working
/// range (the default module: 0.89 at 150 mm), else why the fields do not meet (a projector on
/// the wrong side or turned away).
std::string FieldOverlapProblem(const ModuleDescription& module);

struct UsabilityProblem {
  enum class Cause { kDepthPrecision, kSpotSize, kWindowFit, kPatternSpan, kFieldOverlap };
  Cause cause = Cause::kDepthPrecision;
  std::string text;
};

/// The first of the five problems above (the pattern span: PatternSpanProblem over the working
/// distances, for a `rows` x `cols` matrix read in `window` x `window` windows), or nullopt for a
/// module the decoder can use.
std::optional<UsabilityProblem> FindUsabilityProblem(const ModuleDescription& module, int rows,
                                                     int cols, int window);

}  // namespace sewer3d
