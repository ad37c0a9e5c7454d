// `sewer3d reconstruct`: one pattern image -> decoded spots -> 3D points, depth map, report.

#include <fmt/core.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/input_file.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/io/reconstruction_io.hpp"
#include "sewer3d/triangulate/reconstruct_frame.hpp"

namespace sewer3d::cli {
namespace {

// For a frame that decoded poorly: a question when --image is a colour picture (its channels
// differ), which a pattern image is not; "" otherwise.
std::string ColourHint(const std::string& image_file) {
  const cv::Mat image = ReadImage(image_file, cv::IMREAD_UNCHANGED, kMaxCameraPixels);
  if (image.channels() < 3) return "";
  std::vector<cv::Mat> channels;
  cv::split(image, channels);
  if (cv::norm(channels[0], channels[1], cv::NORM_INF) == 0 &&
      cv::norm(channels[1], channels[2], cv::NORM_INF) == 0) {
    return "";
  }
  return "; it is a colour image, and --image takes the grey pattern image: are --image and "
         "--texture swapped?";
}

}  // namespace

Command AddReconstructCommand(CLI::App& app) {
  struct Args {
    std::string module, image, texture, out;
    double max_edge_steps = FrameReconstructionOptions{}.max_edge_steps;
    SpotFlags spots;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "reconstruct", "Decode a pattern image and triangulate: cloud.ply, depth.tiff, report.json");
  sub->add_option("--module", args->module, "module.json")->required();
  sub->add_option("--image", args->image, "Pattern image (8- or 16-bit)")->required();
  sub->add_option("--texture", args->texture, "Texture image for point colours");
  sub->add_option("--out", args->out, "Output folder")->required();
  sub->add_option("--max-edge-steps", args->max_edge_steps,
                  "Depth map: longest triangle edge, in pattern pitches")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 20.0));
  AddSpotFlags(sub, &args->spots);
  return {
      sub, [args] {
        const LoadedModule loaded = LoadModule(args->module);
        const ModuleDescription& module = loaded.module;
        CheckNotInRunOrWorkspace(args->out, "--out");
        for (const char* name : {"cloud.ply", "depth.tiff", "depth.png", "report.json"}) {
          const std::filesystem::path output = std::filesystem::path(args->out) / name;
          CheckNotAnInput(output, args->image, "--image");
          if (!args->texture.empty()) CheckNotAnInput(output, args->texture, "--texture");
          CheckNotAnInput(output, args->module, "--module");
          CheckNotAnInput(output, loaded.pattern_file, "pattern matrix");
        }
        const cv::Mat image = ReadGreyImage(args->image);
        if (image.cols != module.camera.width || image.rows != module.camera.height) {
          throw FileError(args->image,
                          fmt::format("image is {}x{} but the module's camera is {}x{}", image.cols,
                                      image.rows, module.camera.width, module.camera.height));
        }
        cv::Mat3b texture;
        std::error_code ec;
        if (!args->texture.empty() && std::filesystem::equivalent(args->texture, args->image, ec)) {
          throw InvalidValue("--texture", args->texture +
                                              " is the pattern image itself: give the image "
                                              "taken with the texture light");
        }
        if (!args->texture.empty()) {
          texture = ReadImage(args->texture, cv::IMREAD_COLOR, kMaxCameraPixels);
          if (texture.size() != image.size())
            throw FileError(args->texture, "texture size differs from the pattern image");
        }
        PatternConstraints constraints;
        try {
          constraints = InferConstraints(loaded.pattern);
        } catch (const std::invalid_argument& e) {
          throw FileError(loaded.pattern_file,
                          std::string("cannot decode with this pattern: ") + e.what());
        }
        FrameReconstructionOptions options;
        options.max_edge_steps = args->max_edge_steps;
        args->spots.ApplyTo(options);
        const FrameReconstruction frame =
            ReconstructFrame(module, loaded.pattern, constraints, image,
                             texture.empty() ? nullptr : &texture, options);
        // A failure writes nothing (the outputs of a frame belong together).
        if (frame.report.not_of_module) {
          fmt::print(stderr, "sewer3d: error: {}: {}\n", args->image,
                     NotOfModuleReason(frame.report));
          return 1;
        }
        if (frame.points.empty()) {
          fmt::print(stderr, "sewer3d: error: {}: {}{}\n", args->image,
                     NoPointsReason(frame.report), ColourHint(args->image));
          return 1;
        }
        const std::filesystem::path out = args->out;
        WriteFrameReconstruction(out, frame, args->image);
        fmt::print(
            "{} spots, {} decoded, {} points; wrote {}/cloud.ply, depth.tiff, depth.png, "
            "report.json\n",
            frame.report.spots_found, frame.report.spots_decoded, frame.points.size(),
            out.string());
        if (const std::string doubt = FrameDoubt(frame.report, frame.points.size());
            !doubt.empty()) {
          fmt::print(stderr, "sewer3d: warning: {}: {}{}\n", args->image, doubt,
                     ColourHint(args->image));
        }
        return 0;
      }};
}

}  // namespace sewer3d::cli
