#pragma once
/// \file
/// Human-readable summary of a module and its pattern, shared by `module` and `describe`.

#include "sewer3d/camera/module.hpp"
#include "sewer3d/pattern/binary_array.hpp"

namespace sewer3d::cli {

/// Prints geometry (fields of view, baseline, stereo angle), the disparity range over the
/// working range and the pattern's verified properties. Returns false when the pattern does
/// not span the disparity range or violates its constraints.
bool PrintModuleSummary(const ModuleDescription& module, const BinaryArray& pattern);

}  // namespace sewer3d::cli
