#include "sewer3d/io/rgbd_io.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/ply_io.hpp"
#include "sewer3d/io/reconstruction_io.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {

RgbdFiles RgbdAcquisitionFiles(const std::filesystem::path& rgbd_folder, int module, int counter) {
  char stem[32];
  std::snprintf(stem, sizeof stem, "%06d_", counter);
  const std::filesystem::path folder = rgbd_folder / ("m" + std::to_string(module));
  const std::string s = stem;
  return {folder / (s + "color.png"), folder / (s + "depth.tiff"), folder / (s + "cloud.ply"),
          folder / (s + "report.json")};
}

bool RgbdAcquisitionDone(const RgbdFiles& files) { return IsRegularFile(files.report); }

void WriteRgbdAcquisition(const RgbdFiles& files, const cv::Mat3b& color_bgr,
                          const FrameReconstruction& frame, const std::string& image,
                          const std::string& extra_json) {
  std::vector<Eigen::Vector3d> xyz;
  std::vector<std::array<std::uint8_t, 3>> colours;
  xyz.reserve(frame.points.size());
  for (const FramePoint& p : frame.points) {
    xyz.push_back(p.point_mm);
    if (frame.coloured) colours.push_back(p.rgb);
  }
  WriteFileAtomically(files.color, [&](const auto& t) { WriteImage(t, color_bgr); });
  WriteFileAtomically(files.depth, [&](const auto& t) { WriteImage(t, frame.depth_mm); });
  WriteFileAtomically(files.cloud, [&](const auto& t) { WritePly(t, xyz, colours); });
  // The frame report's own writer gives its fields; the acquisition's are merged over them.
  WriteFileAtomically(files.report, [&](const std::filesystem::path& t) {
    WriteFrameReport(t, frame.report, image);
    nlohmann::json report = nlohmann::json::parse(ReadTextFile(t));
    report.merge_patch(nlohmann::json::parse(extra_json));
    WriteTextFile(t, report.dump(2) + "\n");
  });
}

}  // namespace sewer3d
