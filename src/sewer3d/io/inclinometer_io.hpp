#pragma once
/// \file
/// inclinometer.csv of a capture run (docs/formats.md): `time_s,down_x,down_y,down_z`, the
/// direction of gravity in the carrier frame (any length: it is normalised) at each reading.
/// Errors are FileError naming the file and line.

#include <filesystem>
#include <vector>

#include "sewer3d/run/inclinometer.hpp"

namespace sewer3d {

void WriteInclinometer(const std::filesystem::path& path,
                       const std::vector<InclinometerReading>& readings);

/// Refuses a row with a field that is not a finite number, a direction shorter than 1e-6 (no
/// reading), or a time not after the row before.
std::vector<InclinometerReading> ReadInclinometer(const std::filesystem::path& path);

}  // namespace sewer3d
