// `sewer3d module`: writes the default module (the paper's geometry) and its pattern.

#include <fmt/core.h>

#include <charconv>
#include <filesystem>
#include <string_view>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/camera/module_checks.hpp"
#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/flag_names.hpp"
#include "sewer3d/cli/summary.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/io/pattern_io.hpp"
#include "sewer3d/pattern/default_pattern.hpp"

namespace sewer3d::cli {

std::optional<std::pair<int, int>> ParseSize(const std::string& text) {
  // Digits only, each side 1..32768: "4294967936x480" must not wrap to 640 x 480.
  const size_t x = text.find_first_of("xX");
  if (x == std::string::npos) return std::nullopt;
  const auto side = [](std::string_view digits) -> std::optional<int> {
    int value = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (digits.empty() || digits[0] == '+' || digits[0] == '-' || ec != std::errc() ||
        end != digits.data() + digits.size() || value <= 0 ||
        value > CameraIntrinsics::kMaxImageSide) {
      return std::nullopt;
    }
    return value;
  };
  const std::string_view view(text);
  const auto w = side(view.substr(0, x)), h = side(view.substr(x + 1));
  if (!w || !h) return std::nullopt;
  return std::make_pair(*w, *h);
}

Command AddModuleCommand(CLI::App& app) {
  struct Args {
    std::string out;
    std::string camera_size = "2592x1944";
    DefaultModuleOptions options;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "module", "Write the default module (module.json + pattern) for the paper's geometry");
  sub->add_option("--out", args->out, "Output folder")->required();
  sub->add_option("--camera-size", args->camera_size, "Camera image size WxH (FOV is kept)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& s) {
            return ParseSize(s) ? std::string() : "expected WxH, each side 1..32768, got " + s;
          },
          "WxH"));
  sub->add_option("--hfov-deg", args->options.horizontal_fov_deg, "Horizontal field of view")
      ->capture_default_str()
      ->check(CLI::Range(10.0, 150.0));
  sub->add_option("--stereo-angle-deg", args->options.stereo_angle_deg,
                  "Angle between camera and projector fields where they meet")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 80.0));
  sub->add_option("--pitch-px", args->options.pitch_px, "Pattern element pitch, projector px")
      ->capture_default_str()
      ->check(CLI::Range(2.0, 100.0));
  sub->add_option("--spot-px", args->options.spot_diameter_px, "Spot diameter, projector px")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 100.0));
  return {sub, [args, sub] {
            const auto size = *ParseSize(args->camera_size);
            args->options.camera_width = size.first;
            args->options.camera_height = size.second;
            try {
              args->options.Check();
            } catch (const InvalidValue& e) {
              throw WithFlagNames(e, {{"spot_diameter_px", "--spot-px"},
                                      {"pitch_px", "--pitch-px"},
                                      {"horizontal_fov_deg", "--hfov-deg"},
                                      {"stereo_angle_deg", "--stereo-angle-deg"},
                                      {"camera_size", "--camera-size"}});
            }
            // The geometry's flags, with --camera-size where given (its aspect sets the
            // vertical field of view).
            const std::string geometry = sub->count("--camera-size") > 0
                                             ? "--camera-size, --hfov-deg, --stereo-angle-deg"
                                             : "--hfov-deg, --stereo-angle-deg";
            ModuleDescription module;
            try {
              module = MakeDefaultModule(args->options);
              module.Check();
            } catch (const InvalidValue& e) {  // valid options, but no valid module from them
              throw InvalidValue(geometry,
                                 fmt::format("this geometry gives no valid module ({}: {}): choose "
                                             "a wider field of view or a smaller stereo angle",
                                             e.field(), e.problem()));
            }
            const std::filesystem::path dir = args->out;
            CheckNotInRunOrWorkspace(dir, "--out");
            const BinaryArray pattern = DefaultPatternArray();
            const SubmapSearchOptions search = DefaultPatternSearchOptions();
            // A module the decoder cannot use is refused before anything is written.
            if (const auto problem = FindUsabilityProblem(module, pattern.rows, pattern.cols,
                                                          search.constraints.window)) {
              using Cause = UsabilityProblem::Cause;
              switch (problem->cause) {
                case Cause::kSpotSize:
                  throw InvalidValue("--pitch-px, --spot-px", problem->text);
                case Cause::kWindowFit:
                  throw InvalidValue("--pitch-px", problem->text);
                case Cause::kPatternSpan:
                  throw InvalidValue(
                      geometry, problem->text + ": choose a smaller stereo angle or field of view");
                case Cause::kDepthPrecision:
                case Cause::kFieldOverlap:
                  throw InvalidValue(geometry, problem->text);
              }
            }
            for (const std::filesystem::path& file :
                 {dir / module.pattern.matrix_path,
                  PatternSidecarPath(dir / module.pattern.matrix_path), dir / "pattern_preview.png",
                  dir / "module.json"})
              CheckOutputFile(file);  // all before any: a refusal leaves none written
            WritePatternMatrix(dir / module.pattern.matrix_path, pattern);
            WritePatternSidecar(PatternSidecarPath(dir / module.pattern.matrix_path),
                                {&search, nullptr, "shipped"},
                                VerifyPattern(pattern, search.constraints));
            WritePatternPreview(dir / "pattern_preview.png", pattern, 8, search.constraints.window);
            SaveModule(dir / "module.json", module);
            const DefaultModuleGeometry g = DescribeDefaultModule(args->options);
            fmt::print("wrote {}/module.json, {}, pattern.json, pattern_preview.png\n",
                       dir.string(), module.pattern.matrix_path);
            fmt::print(
                "default module: stereo angle {:g} deg where the fields meet at {:g} mm, "
                "fields tilted {:g} deg each; lens field {:g} x {:.1f} deg, camera sees "
                "{:.1f} to {:.1f} deg along the carrier axis\n",
                args->options.stereo_angle_deg, args->options.meeting_distance_mm, g.field_tilt_deg,
                args->options.horizontal_fov_deg, g.lens_vertical_fov_deg, g.field_top_deg,
                g.field_bottom_deg);
            PrintModuleSummary(module, pattern);
            return 0;
          }};
}

}  // namespace sewer3d::cli
