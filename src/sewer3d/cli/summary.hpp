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

}  // namespace sewer3d::cli
