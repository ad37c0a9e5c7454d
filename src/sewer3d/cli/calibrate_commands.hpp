#pragma once
/// \file
/// Pieces of `sewer3d calibrate` kept in their own files.

#include <CLI/CLI.hpp>
#include <string>

#include "sewer3d/cli/command.hpp"

namespace sewer3d::cli {

/// The --board option of the calibrate subcommands: COLSxROWS inner corners, each 3 to 200.
CLI::Option* AddBoardOption(CLI::App& sub, std::string& board);

/// The --square-mm option (board square size): 0.1..1000 mm (a board OpenCV can use).
CLI::Option* AddSquareOption(CLI::App& sub, double& square_mm);

/// `sewer3d calibrate module` (docs/calibration.md), registered under `calibrate`.
Command AddCalibrateModuleCommand(CLI::App& calibrate);

}  // namespace sewer3d::cli
