// `sewer3d reconstruct`: one pattern image -> decoded spots -> 3D points, depth map, report.

#include <fmt/core.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "sewer3d/cli/command.hpp"
#include "sewer3d/decode/decoder.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/io/ply_io.hpp"
#include "sewer3d/triangulate/correspondences.hpp"
#include "sewer3d/triangulate/depth_map.hpp"

namespace sewer3d::cli {

Command AddReconstructCommand(CLI::App& app) {
  struct Args {
    std::string module, image, texture, out;
    double max_edge_steps = 5.5;
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
  return {
      sub, [args] {
        using Clock = std::chrono::steady_clock;
        const LoadedModule loaded = LoadModule(args->module);
        const ModuleDescription& module = loaded.module;
        const cv::Mat image = ReadGreyImage(args->image);
        if (image.cols != module.camera.width || image.rows != module.camera.height) {
          throw FileError(args->image,
                          fmt::format("image is {}x{} but the module's camera is {}x{}", image.cols,
                                      image.rows, module.camera.width, module.camera.height));
        }
        cv::Mat texture;
        if (!args->texture.empty()) {
          texture = ReadImage(args->texture, cv::IMREAD_COLOR);
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
        Decoder decoder(module, loaded.pattern, constraints, DecoderOptions{});
        const DecodeResult decoded = decoder.Decode(image);
        std::vector<CodedObservation> observations;
        for (const SpotCode& c : decoded.codes)
          observations.push_back({decoded.spots[c.spot].centre_px, c.row, c.col});
        auto t = Clock::now();
        TriangulationStats tri_stats;
        auto points = TriangulateObservations(module, loaded.pattern.rows, loaded.pattern.cols,
                                              observations, TriangulationOptions{}, &tri_stats);
        const int outliers = RejectDepthOutliers(points, observations);
        const double seconds_triangulate = std::chrono::duration<double>(Clock::now() - t).count();
        t = Clock::now();
        std::vector<Eigen::Vector2d> pixels;
        std::vector<double> depths;
        std::vector<Eigen::Vector3d> xyz;
        std::vector<std::array<std::uint8_t, 3>> colours;
        for (const auto& p : points) {
          const Eigen::Vector2d& px = observations[p.observation].camera_px;
          pixels.push_back(px);
          depths.push_back(p.point_mm.z());
          xyz.push_back(p.point_mm);
          if (!texture.empty()) {
            const cv::Vec3b bgr = texture.at<cv::Vec3b>(static_cast<int>(std::lround(px.y())),
                                                        static_cast<int>(std::lround(px.x())));
            colours.push_back({bgr[2], bgr[1], bgr[0]});
          }
        }
        const cv::Mat1f depth = InterpolateDepth(image.size(), pixels, depths,
                                                 args->max_edge_steps * module.pattern.pitch_px);
        const double seconds_depth = std::chrono::duration<double>(Clock::now() - t).count();
        const std::filesystem::path out = args->out;
        std::filesystem::create_directories(out);
        WritePly(out / "cloud.ply", xyz, colours);
        WriteImage(out / "depth.tiff", depth);
        WriteDepthPreview(out / "depth.png", depth);
        nlohmann::json report;
        report["image"] = args->image;
        report["spots_found"] = decoded.spots.size();
        report["lattice_groups"] = decoded.lattice.groups;
        report["lattice_conflicts"] = decoded.lattice.conflicts;
        report["windows_read"] = decoded.stats.windows_read;
        report["windows_decoded"] = decoded.stats.windows_decoded;
        report["bits_corrected"] = decoded.stats.bits_corrected;
        report["spots_decoded"] = decoded.codes.size();
        report["rejected"] = {{"votes_split_or_too_few", decoded.stats.spots_ambiguous},
                              {"beyond_lens_fold", tri_stats.unprojectable},
                              {"no_tile_on_epipolar_line", tri_stats.no_element},
                              {"several_tiles_fit", tri_stats.ambiguous},
                              {"depth_outlier_or_isolated", outliers}};
        report["points"] = points.size();
        report["seconds"] = {
            {"binarise", decoded.seconds_binarise}, {"spots", decoded.seconds_spots},
            {"lattice", decoded.seconds_lattice},   {"codewords", decoded.seconds_codewords},
            {"triangulate", seconds_triangulate},   {"depth_map", seconds_depth}};
        std::ofstream(out / "report.json") << report.dump(2) << "\n";
        fmt::print(
            "{} spots, {} decoded, {} points; wrote {}/cloud.ply, depth.tiff, depth.png, "
            "report.json\n",
            decoded.spots.size(), decoded.codes.size(), points.size(), out.string());
        if (points.empty()) {
          fmt::print(stderr, "sewer3d: error: {}: no spot pattern decoded (see {}/report.json)\n",
                     args->image, out.string());
          return 1;
        }
        return 0;
      }};
}

}  // namespace sewer3d::cli
