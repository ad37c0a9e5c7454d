// The options `calibrate camera` and `calibrate module` share: the board's inner corners and
// its square size.

#include <string>

#include "sewer3d/cli/calibrate_commands.hpp"
#include "sewer3d/cli/command.hpp"

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

}  // namespace sewer3d::cli
