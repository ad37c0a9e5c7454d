// `sewer3d calibrate module`: camera, projector and their extrinsics from checkerboard
// captures (docs/calibration.md).

#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "sewer3d/calib/module_from_captures.hpp"
#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/calibrate_commands.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/calibration_io.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/module_io.hpp"

namespace sewer3d::cli {
namespace {

namespace fs = std::filesystem;

struct ModuleArgs {
  std::string captures, board = "9x6", out, nominal;
  double square_mm = 10.0;
  bool quiet = false;
};

int RunModule(const ModuleArgs& a) {
  const auto board_size = ParseSize(a.board);
  CheckFileNotInRunOrWorkspace(a.out, "--out");
  CheckOutputFile(a.out);  // before minutes of work
  std::error_code ec;
  if (!a.nominal.empty() && fs::equivalent(a.out, a.nominal, ec))
    throw InvalidValue("--out",
                       a.out + " is the --nominal module; write the calibration beside it");
  // pattern.png is written beside the module file: they must be two files.
  if (fs::path(a.out).filename() == "pattern.png")
    throw InvalidValue("--out", "names the module file (JSON), got " + a.out +
                                    ": pattern.png is written beside it");
  CheckOutputFile(fs::path(a.out).parent_path() / "pattern.png");
  if (IsRegularFile(fs::path(a.out).parent_path() / "texture.png")) {
    throw InvalidValue("--out", a.out +
                                    " lies in a pose folder (it holds texture.png): the "
                                    "pattern.png written beside the module would replace "
                                    "its capture; choose another folder");
  }
  const std::vector<fs::path> poses = PoseFolders(a.captures);
  if (poses.size() < 3) {
    throw FileError(
        a.captures,
        fmt::format("{} pose folders with texture.png and pattern.png; calibration needs at "
                    "least 3 (layout: docs/calibration.md)",
                    poses.size()));
  }
  const fs::path first_image = poses[0] / "texture.png";
  const cv::Size size = ReadImage(first_image, cv::IMREAD_GRAYSCALE, kMaxCameraPixels).size();
  const NominalModule nominal = LoadNominal(a.nominal, first_image, size);
  BoardLayout board_layout;
  board_layout.cols = board_size->first;
  board_layout.rows = board_size->second;
  board_layout.square_mm = a.square_mm;
  CheckBoardFile(a.captures, board_layout);
  ModuleCalibrator calibrator(nominal.module, nominal.pattern, nominal.constraints, board_layout);
  const CaptureTally tally = AddCaptures(calibrator, poses, size, a.board, a.quiet);
  const std::vector<std::string>& used = tally.used;
  if (used.size() < 3) {
    const std::string hint =
        2 * static_cast<std::size_t>(tally.repeated) >= poses.size() - used.size()
            ? fmt::format("{} poses repeat one used before: copies or links of one capture?",
                          tally.repeated)
        : a.nominal.empty()
            ? std::string("each skipped pose is named above")
            : "were these captures made with the --nominal module " + a.nominal + "?";
    fmt::print(stderr,
               "sewer3d: error: {} of {} poses usable; module calibration needs at least 3 ({})\n",
               used.size(), poses.size(), hint);
    return 1;
  }
  ModuleFromCapturesResult calibrated;
  try {
    calibrated = calibrator.Calibrate();
  } catch (const std::invalid_argument& e) {
    // The estimate left the valid range: the captures do not fix the module.
    fmt::print(stderr,
               "sewer3d: error: calibration failed: the estimate is not a valid module ({}); "
               "check that each pose's texture and pattern images belong together\n",
               e.what());
    return 1;
  }
  ModuleDescription module = calibrated.module;
  CheckCalibratedScale(module, nominal.module, a.square_mm);
  module.pattern.matrix_path = "pattern.png";
  // Only the calibration's own extra member: none of the nominal module's.
  module.source_json = ModuleCalibrationMember(
      calibrated.second_pass, static_cast<int>(used.size()), static_cast<int>(poses.size()));
  SaveModule(a.out, module);
  WritePatternMatrix(fs::path(a.out).parent_path() / "pattern.png", nominal.pattern);
  PrintModuleCalibration(calibrated.second_pass, used, poses.size());
  fmt::print("wrote {} and pattern.png beside it\n", a.out);
  return 0;
}

}  // namespace

Command AddCalibrateModuleCommand(CLI::App& calibrate) {
  auto args = std::make_shared<ModuleArgs>();
  CLI::App* sub = calibrate.add_subcommand(
      "module", "Camera, projector and their extrinsics from checkerboard captures");
  sub->add_option("--captures", args->captures,
                  "Folder of pose folders (pose_NN/texture.png, pattern.png)")
      ->required()
      ->check(CLI::ExistingDirectory);
  AddBoardOption(*sub, args->board);
  AddSquareOption(*sub, args->square_mm);
  sub->add_option("--out", args->out, "Calibrated module.json (pattern.png is written beside it)")
      ->required();
  sub->add_option(
         "--nominal", args->nominal,
         "Design module (pattern, projector size, rough geometry); default: the default module")
      ->check(CLI::ExistingFile);
  sub->add_flag("--quiet", args->quiet, "No progress bar");
  return {sub, [args] { return RunModule(*args); }};
}

}  // namespace sewer3d::cli
