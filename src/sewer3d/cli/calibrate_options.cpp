// The options `calibrate camera` and `calibrate module` share: the board's inner corners and
// its square size, and the checks of the square size against the captures and the module.

#include <fmt/core.h>

#include <cmath>
#include <string>

#include "sewer3d/cli/calibrate_commands.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/calibration_io.hpp"

namespace sewer3d::cli {

CLI::Option* AddBoardOption(CLI::App& sub, std::string& board) {
  return sub.add_option("--board", board, "Inner corners COLSxROWS")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& s) {
            constexpr int kMaxCorners = 200;  // a printable board has far fewer
            const auto size = ParseSize(s);
            const auto fits = [](int n) { return n >= 3 && n <= kMaxCorners; };
            return size && fits(size->first) && fits(size->second)
                       ? std::string()
                       : "expected COLSxROWS inner corners, each 3 to 200, got " + s;
          },
          "COLSxROWS"));
}

CLI::Option* AddSquareOption(CLI::App& sub, double& square_mm) {
  return sub.add_option("--square-mm", square_mm, "Square size, mm")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1000.0));
}

void CheckBoardFile(const std::filesystem::path& captures, const BoardLayout& layout) {
  const std::filesystem::path file = captures / "board.json";
  if (!IsRegularFile(file)) return;
  const BoardLayout written = ReadBoardLayout(file, layout);
  const double square_mm = written.square_mm;
  if (std::abs(square_mm - layout.square_mm) > 1e-6 * square_mm) {
    throw InvalidValue(
        "--square-mm",
        fmt::format("{} mm, but {} says {} mm: every length of the module would "
                    "be scaled by {:.3g}",
                    layout.square_mm, file.string(), square_mm, layout.square_mm / square_mm));
  }
  const int cols = written.cols, rows = written.rows;
  if (cols != layout.cols || rows != layout.rows) {
    throw InvalidValue("--board", fmt::format("{}x{}, but {} says {}x{}", layout.cols, layout.rows,
                                              file.string(), cols, rows));
  }
}

void CheckCalibratedScale(const ModuleDescription& module, const ModuleDescription& nominal,
                          double square_mm) {
  // Every length of the estimate scales with the board's square: a baseline out of range, or
  // far from the design's, is a wrong --square-mm (board.json gone) far more often than a
  // wrong build.
  try {
    module.Check();
  } catch (const InvalidValue& e) {
    if (e.field().rfind("projector_from_camera", 0) != 0) throw;
    throw InvalidValue("--square-mm", fmt::format("{:g} mm makes the calibrated module's {}: "
                                                  "{}; is it the board's square size?",
                                                  square_mm, e.field(), e.problem()));
  }
  const double b = module.projector_from_camera.translation.norm();
  const double design = nominal.projector_from_camera.translation.norm();
  if (b >= 0.5 * design && b <= 2.0 * design) return;
  throw InvalidValue("--square-mm",
                     fmt::format("{:g} mm makes the calibrated baseline {:.2f} mm, {:.2f} x the "
                                 "nominal module's {:.2f} mm; is it the board's square size?",
                                 square_mm, b, b / design, design));
}

}  // namespace sewer3d::cli
