#include "sewer3d/io/reconstruction_io.hpp"

#include <nlohmann/json.hpp>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/ply_io.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {

void WriteFrameReconstruction(const std::filesystem::path& folder, const FrameReconstruction& frame,
                              const std::string& image) {
  std::vector<Eigen::Vector3d> xyz;
  std::vector<std::array<std::uint8_t, 3>> colours;
  xyz.reserve(frame.points.size());
  for (const FramePoint& p : frame.points) {
    xyz.push_back(p.point_mm);
    if (frame.coloured) colours.push_back(p.rgb);
  }
  for (const char* name : {"cloud.ply", "depth.tiff", "depth.png", "report.json"})
    CheckOutputFile(folder / name);  // all before any: a refusal leaves none written
  CreateOutputFolder(folder);
  WritePly(folder / "cloud.ply", xyz, colours);
  WriteImage(folder / "depth.tiff", frame.depth_mm);
  WriteDepthPreview(folder / "depth.png", frame.depth_mm);
  WriteFrameReport(folder / "report.json", frame.report, image);
}

void WriteFrameReport(const std::filesystem::path& path, const FrameReport& r,
                      const std::string& image) {
  nlohmann::json report;  // a std::map underneath: keys come out sorted, as report.json has them
  report["image"] = image;
  report["spots_found"] = r.spots_found;
  report["lattice_groups"] = r.lattice_groups;
  report["lattice_conflicts"] = r.lattice_conflicts;
  report["windows_read"] = r.windows_read;
  report["windows_decoded"] = r.windows_decoded;
  report["bits_corrected"] = r.bits_corrected;
  report["spots_decoded"] = r.spots_decoded;
  report["lost_spots_found"] = r.lost_spots_found;
  report["rejected"] = {{"votes_split_or_too_few", r.rejected.votes_split_or_too_few},
                        {"beyond_lens_fold", r.rejected.beyond_lens_fold},
                        {"no_tile_on_epipolar_line", r.rejected.no_tile_on_epipolar_line},
                        {"several_tiles_fit", r.rejected.several_tiles_fit},
                        {"element_claimed_twice", r.rejected.element_claimed_twice},
                        {"cut_by_step", r.rejected.cut_by_step},
                        {"depth_outlier_or_isolated", r.rejected.depth_outlier_or_isolated},
                        {"not_of_module", r.rejected.not_of_module}};
  report["epipolar_tolerance_px"] = r.epipolar_tolerance_px;
  report["not_of_module"] = r.not_of_module;
  report["points"] = r.points;
  report["depth_pixels"] = r.depth_pixels;
  report["seconds"] = {{"binarise", r.seconds.binarise},       {"spots", r.seconds.spots},
                       {"lattice", r.seconds.lattice},         {"codewords", r.seconds.codewords},
                       {"triangulate", r.seconds.triangulate}, {"lost_spots", r.seconds.lost_spots},
                       {"depth_map", r.seconds.depth_map}};
  WriteTextFile(path, report.dump(2) + "\n");
}

}  // namespace sewer3d
