#pragma once
/// \file
/// Pieces of `sewer3d calibrate` kept in their own files.

#include <CLI/CLI.hpp>
#include <string>

#include "sewer3d/cli/command.hpp"

namespace sewer3d::cli {

/// The --board option of the calibrate subcommands: COLSxROWS, at least 3x3 inner corners.
CLI::Option* AddBoardOption(CLI::App& sub, std::string& board);

/// `sewer3d calibrate module` (docs/calibration.md), registered under `calibrate`.
Command AddCalibrateModuleCommand(CLI::App& calibrate);

}  // namespace sewer3d::cli
