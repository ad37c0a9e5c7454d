// `sewer3d simulate calibration`: rendered checkerboard captures of a module for calibration,
// each pose twice (board lit, pattern off; pattern on, ambient off), with the truth.

#include <fmt/core.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/calibrate_commands.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/progress_bar.hpp"
#include "sewer3d/cli/simulate_commands.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/sim/board.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/sim/spot_errors.hpp"
#include "sewer3d/simio/scene_io.hpp"
#include "sewer3d/simio/truth_io.hpp"

namespace sewer3d::cli {
namespace {

// Makes `out` ready for `poses` pose folders: those of an earlier simulated capture beyond
// `poses` are removed (a calibration would take them for this one's); pose folders that
// simulate calibration did not write (no truth/poses.json) are refused, never removed.
void PrepareCaptureFolder(const std::filesystem::path& out, int poses) {
  if (!std::filesystem::is_directory(out)) return;
  if (std::filesystem::is_regular_file(out / "run.json"))
    throw FileError(out, "holds a capture run (run.json); choose another --out");
  static const std::regex pose_name("pose_([0-9]+)");
  const bool simulated = std::filesystem::is_regular_file(out / "truth" / "poses.json");
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::directory_iterator(out)) {
    std::smatch m;
    const std::string name = entry.path().filename().string();
    if (!std::regex_match(name, m, pose_name)) continue;
    if (!simulated) {
      throw FileError(out,
                      "holds pose folders that simulate calibration did not write; "
                      "choose another --out");
    }
    if (m[1].length() > 6 || std::stoi(m[1].str()) >= poses) stale.push_back(entry.path());
  }
  for (const auto& p : stale) std::filesystem::remove_all(p);
}

}  // namespace

void AddCalibrationCommand(CLI::App& sim, CalibrationArgs& a) {
  CLI::App* sub =
      sim.add_subcommand("calibration", "Render checkerboard captures of a module for calibration");
  sub->add_option("--module", a.module, "The true module.json")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--poses", a.poses, "Board poses")
      ->capture_default_str()
      ->check(CLI::Range(1, 200));
  sub->add_option("--out", a.out, "Capture folder")->required();
  sub->add_option("--seed", a.seed, "Poses and noise seed")->capture_default_str()->check(Digits());
  AddBoardOption(*sub, a.board);
  AddSquareOption(*sub, a.square_mm);
  sub->add_option("--supersampling", a.supersampling,
                  "S x S samples per pixel of the pattern images")
      ->capture_default_str()
      ->check(CLI::Range(1, 16));
  sub->add_option("--texture-supersampling", a.texture_supersampling,
                  "S x S samples per pixel of the board images (corner accuracy needs S >= 4)")
      ->capture_default_str()
      ->check(CLI::Range(1, 16));
  sub->add_option("--realism", a.realism,
                  "Error sources of a real module: ideal (none) or paper (its projector's and "
                  "lenses'; a printed board has no relief)")
      ->capture_default_str()
      ->check(CLI::IsMember({"ideal", "paper"}));
  sub->add_flag("--quiet", a.quiet, "No progress bar");
  a.app = sub;
}

int RunCalibration(const CalibrationArgs& a) {
  const auto size = ParseSize(a.board);  // checked by AddBoardOption
  const LoadedModule loaded = LoadModule(a.module);
  Checkerboard board;
  board.cols = size->first;
  board.rows = size->second;
  board.square_mm = a.square_mm;
  std::vector<Rigid3d> poses;
  try {
    poses = RandomBoardPoses(loaded.module, board, a.poses, a.seed);
  } catch (const InvalidValue& e) {  // named as the flags
    if (e.field() == "square_mm") throw InvalidValue("--square-mm", e.problem());
    if (e.field() == "board") throw InvalidValue("--board, --square-mm", e.problem());
    throw;
  }
  const std::filesystem::path out(a.out);
  PrepareCaptureFolder(out, a.poses);
  CheckNotInRunOrWorkspace(out, "--out");
  ProgressBar progress(a.quiet);
  const nlohmann::json board_json = {
      {"cols", board.cols}, {"rows", board.rows}, {"square_mm", board.square_mm}};
  WriteTextFile(out / "board.json", board_json.dump(2) + "\n");
  ModuleDescription truth_module = loaded.module;  // loadable on its own: pattern beside it
  truth_module.pattern.matrix_path = "pattern.png";
  SaveModule(out / "truth" / "module.json", truth_module);
  WritePatternMatrix(out / "truth" / "pattern.png", loaded.pattern);
  for (size_t i = 0; i < poses.size(); ++i) {
    const std::filesystem::path dir = out / fmt::format("pose_{:02d}", i);
    const BoardSurface surface(board, poses[i]);
    RenderOptions o;
    // A printed board: no relief, no scattering; the module file is the truth here.
    o.spot_errors = ModuleOwnErrors(*RealismProfile(a.realism));
    o.supersampling = a.texture_supersampling;
    o.seed = a.seed * 1000 + i;
    o.images = RenderImages::kTexture;  // board lit, pattern off
    const RenderedFrame texture = RenderFrame(loaded.module, loaded.pattern, surface, o);
    WriteTextureImage(dir / "texture.png", texture, o.sensor.bits);
    o.supersampling = a.supersampling;
    o.images = RenderImages::kPattern;  // pattern on, ambient light off
    o.ambient_level = 0.0;
    o.truth_depth = false;
    const RenderedFrame pattern = RenderFrame(loaded.module, loaded.pattern, surface, o);
    WritePatternImage(dir / "pattern.png", pattern, o.sensor.bits);
    progress.Update("simulate calibration", static_cast<int>(i + 1), static_cast<int>(poses.size()),
                    "poses");
  }
  WriteCalibrationTruth(out / "truth" / "poses.json", {board, a.realism, poses});
  fmt::print(
      "wrote {} poses of a {}x{} board ({} mm squares) to {}: pose_NN/texture.png, pattern.png; "
      "truth/\n",
      poses.size(), board.cols, board.rows, board.square_mm, a.out);
  return 0;
}

}  // namespace sewer3d::cli
