#pragma once
/// \file
/// Pieces of `sewer3d calibrate` kept in their own files.

#include <CLI/CLI.hpp>
#include <cstddef>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "sewer3d/calib/module_from_captures.hpp"
#include "sewer3d/camera/module.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/pattern/binary_array.hpp"
#include "sewer3d/pattern/constraints.hpp"

namespace sewer3d::cli {

/// The --board option of the calibrate subcommands: COLSxROWS inner corners, each 3 to 200.
CLI::Option* AddBoardOption(CLI::App& sub, std::string& board);

/// The --square-mm option (board square size): 0.1..1000 mm (a board OpenCV can use).
CLI::Option* AddSquareOption(CLI::App& sub, double& square_mm);

/// The captures' board.json (`simulate calibration` writes one) must agree with --board and
/// --square-mm: another square size would scale every length of the module without a word.
/// InvalidValue naming the flag; nothing when there is no board.json.
void CheckBoardFile(const std::filesystem::path& captures, const BoardLayout& layout);

/// The calibrated `module` must be valid and its baseline within 0.5–2 × the `nominal`
/// module's: else InvalidValue naming --square-mm (every length scales with the square).
void CheckCalibratedScale(const ModuleDescription& module, const ModuleDescription& nominal,
                          double square_mm);

/// `sewer3d calibrate module` (docs/calibration.md), registered under `calibrate`.
Command AddCalibrateModuleCommand(CLI::App& calibrate);

// Its steps (calibrate_module_steps.cpp).

/// The pose folders below `captures` that hold texture.png and pattern.png, sorted; a folder
/// with only one of the two is printed as skipped.
std::vector<std::filesystem::path> PoseFolders(const std::filesystem::path& captures);

/// The nominal (design) module: pattern, projector size, and a geometry close enough to
/// predict the lattice and pick the pattern tile.
struct NominalModule {
  ModuleDescription module;
  BinaryArray pattern;
  PatternConstraints constraints;
};

/// The module of `nominal_file`, or the default module at the images' `size` when it is "";
/// FileError naming `first_image` when the sizes differ.
NominalModule LoadNominal(const std::string& nominal_file, const std::filesystem::path& first_image,
                          const cv::Size& size);

/// Adds every pose's captures (progress bar unless quiet); returns the names of the poses
/// used and how many repeated an earlier one, and prints why each other one was skipped
/// (`board`: the --board text).
struct CaptureTally {
  std::vector<std::string> used;  ///< pose folder names used, in order
  int repeated = 0;               ///< poses skipped as a repeat of one used before
};
CaptureTally AddCaptures(ModuleCalibrator& calibrator,
                         const std::vector<std::filesystem::path>& poses, const cv::Size& size,
                         const std::string& board, bool quiet);

/// The estimate with its uncertainties and each used pose's reprojection RMS.
void PrintModuleCalibration(const ModuleCalibrationResult& r, const std::vector<std::string>& used,
                            std::size_t poses);

}  // namespace sewer3d::cli
