#pragma once
/// \file
/// A module's reference light (texture/shading.hpp) as the RGB-D stage keeps it:
/// `WS/rgbd/reference/m<k>.json` (docs/rgbd.md), written atomically. Errors are FileError.

#include <filesystem>
#include <string>

#include "sewer3d/texture/module_gains.hpp"
#include "sewer3d/texture/shading.hpp"

namespace sewer3d {

/// Writes the reference (grid of log2 BGR values, level, geometry options) and `report_json`
/// (a JSON object as text, e.g. the estimator's report) under "report".
void WriteReferenceLight(const std::filesystem::path& path, const ReferenceLight& reference,
                         const std::string& report_json);

/// Reads what WriteReferenceLight wrote; FileError naming the file and field.
ReferenceLight ReadReferenceLight(const std::filesystem::path& path);

/// The modules' colour gains (texture/module_gains.hpp) as `WS/rgbd/reference/module_gains.json`:
/// {"gains_bgr": [[b, g, r], …], "seams": n, "rms_log_residual": x}.
void WriteModuleGains(const std::filesystem::path& path, const ModuleGains& gains);
/// Reads it; FileError naming the file and field, also when it holds another number of modules.
ModuleGains ReadModuleGains(const std::filesystem::path& path, int modules);

}  // namespace sewer3d
