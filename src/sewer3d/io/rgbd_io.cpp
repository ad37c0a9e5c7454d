#include "sewer3d/io/rgbd_io.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/ply_io.hpp"
#include "sewer3d/io/reconstruction_io.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

void Rename(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::error_code ec;
  std::filesystem::rename(from, to, ec);
  if (ec) throw FileError(to, "cannot rename the finished temporary file over it: " + ec.message());
}

}  // namespace

RgbdFiles RgbdAcquisitionFiles(const std::filesystem::path& rgbd_folder, int module, int counter) {
  char name[32], stem[32];
  std::snprintf(name, sizeof name, "m%d", module);
  std::snprintf(stem, sizeof stem, "%06d_", counter);
  const std::filesystem::path folder = rgbd_folder / name;
  const std::string s = stem;
  return {folder / (s + "color.png"),         folder / (s + "depth.tiff"),
          folder / (s + "depth_preview.png"), folder / (s + "cloud.ply"),
          folder / (s + "geometry.json"),     folder / (s + "report.json")};
}

std::string RgbdDamagedFile(const RgbdFiles& files) {
  if (!IsRegularFile(files.report)) return "";
  // A report that does not parse is left to its reader, which names it.
  const nlohmann::json report = nlohmann::json::parse(ReadTextFile(files.report), nullptr, false);
  if (report.is_discarded() || !report.is_object() || !report.contains("file_bytes")) return "";
  const nlohmann::json& sizes = report["file_bytes"];
  if (!sizes.is_object()) return files.report.string();
  for (const auto& [name, bytes] : sizes.items()) {
    const std::filesystem::path file = files.report.parent_path() / name;
    std::error_code ec;
    if (!IsRegularFile(file) || !bytes.is_number_unsigned() ||
        std::filesystem::file_size(file, ec) != bytes.get<std::uintmax_t>() || ec)
      return file.string();
  }
  return "";
}

bool RgbdAcquisitionDone(const RgbdFiles& files) {
  return IsRegularFile(files.report) && RgbdDamagedFile(files).empty();
}

bool RgbdGeometryDone(const RgbdFiles& files) { return IsRegularFile(files.geometry); }

void WriteRgbdGeometry(const RgbdFiles& files, const FrameReconstruction& frame,
                       const std::string& image, const std::string& extra_json) {
  // The single-frame writer fills a temporary folder in the same file system; each file is
  // renamed into place complete, the geometry report last.
  const std::filesystem::path temporary = TemporaryPathFor(files.geometry);
  try {
    WriteFrameReconstruction(temporary, frame, image);
    Rename(temporary / "depth.tiff", files.depth);
    Rename(temporary / "depth.png", files.depth_preview);
    Rename(temporary / "cloud.ply", files.cloud);
    nlohmann::json report = nlohmann::json::parse(ReadTextFile(temporary / "report.json"));
    report.merge_patch(nlohmann::json::parse(extra_json));
    WriteTextFileAtomically(files.geometry, report.dump(2) + "\n");
  } catch (const FileError& e) {
    std::error_code ignored;
    std::filesystem::remove_all(temporary, ignored);
    // A write into the temporary folder failed (a full disk): name the file it was to become.
    if (e.path().parent_path() != temporary) throw;
    const std::string problem = std::string(e.what()).substr(ShownPath(e.path()).size() + 2);
    const std::string name = e.path().filename().string();
    const std::filesystem::path target = name == "depth.tiff"  ? files.depth
                                         : name == "depth.png" ? files.depth_preview
                                         : name == "cloud.ply" ? files.cloud
                                                               : files.geometry;
    throw FileError(target, problem);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove_all(temporary, ignored);
    throw;
  }
  RemoveFolder(temporary);
}

RgbdGeometry ReadRgbdGeometry(const RgbdFiles& files) {
  RgbdGeometry g;
  const cv::Mat depth = ReadImage(files.depth, cv::IMREAD_UNCHANGED);
  if (depth.type() != CV_32FC1) throw FileError(files.depth, "not a float32 one-channel depth map");
  g.depth_mm = depth;
  g.points = ReadPlyPoints(files.cloud);
  g.report_json = ReadTextFile(files.geometry);
  const nlohmann::json j = nlohmann::json::parse(g.report_json, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw FileError(files.geometry, "not a JSON object");
  return g;
}

void WriteRgbdColour(const RgbdFiles& files, const cv::Mat3b& color_bgr,
                     const std::vector<Eigen::Vector3d>& points,
                     const std::vector<std::array<std::uint8_t, 3>>& colours,
                     const std::string& report_json) {
  WriteFileAtomically(files.color, [&](const auto& t) { WriteImage(t, color_bgr); });
  WriteFileAtomically(files.cloud, [&](const auto& t) { WritePly(t, points, colours); });
  nlohmann::json report = nlohmann::json::parse(report_json);
  for (const std::filesystem::path* file : {&files.depth, &files.color, &files.cloud}) {
    std::error_code ec;
    const std::uintmax_t bytes = std::filesystem::file_size(*file, ec);
    if (!ec) report["file_bytes"][file->filename().string()] = bytes;
  }
  WriteTextFileAtomically(files.report, report.dump(2) + "\n");
}

}  // namespace sewer3d
