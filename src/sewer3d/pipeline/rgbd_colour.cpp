#include "sewer3d/pipeline/rgbd_colour.hpp"

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/pipeline/acquisition_images.hpp"

namespace sewer3d {
namespace {

using Clock = std::chrono::steady_clock;

// The colour of every cloud point: the colour image at the point's projection (nearest pixel),
// black outside the image.
std::vector<std::array<std::uint8_t, 3>> PointColours(const std::vector<Eigen::Vector3d>& points,
                                                      const CameraModel& camera,
                                                      const cv::Mat3b& color_bgr) {
  std::vector<std::array<std::uint8_t, 3>> colours(points.size(), {0, 0, 0});
  for (size_t i = 0; i < points.size(); ++i) {
    const auto px = camera.Project(points[i]);
    if (!px) continue;
    const int u = static_cast<int>(std::lround(px->x())),
              v = static_cast<int>(std::lround(px->y()));
    if (u < 0 || v < 0 || u >= color_bgr.cols || v >= color_bgr.rows) continue;
    const cv::Vec3b bgr = color_bgr(v, u);
    colours[i] = {bgr[2], bgr[1], bgr[0]};
  }
  return colours;
}

}  // namespace

RgbdAcquisitionResult RgbdColourPass(const CaptureRun& run, const Acquisition& a,
                                     const std::filesystem::path& rgbd_folder) {
  RgbdAcquisitionResult result;
  result.module = a.module;
  result.counter = a.counter;
  const RgbdFiles files = RgbdAcquisitionFiles(rgbd_folder, a.module, a.counter);
  if (RgbdAcquisitionDone(files)) {
    result.status = RgbdAcquisitionResult::Status::kSkipped;
    return result;
  }
  if (!RgbdGeometryDone(files)) {
    FailAcquisition(result, files.geometry, "no geometry: the geometry pass failed");
    return result;
  }
  const auto start = Clock::now();
  try {
    const RgbdGeometry geometry = ReadRgbdGeometry(files);
    const std::filesystem::path texture_file =
        AcquisitionImageFile(run, a, ImageKind::kTextureBefore);
    const cv::Mat3b color = ReadTextureImage(run, a, ImageKind::kTextureBefore);
    const CameraModel camera(run.rig.modules.at(a.module).module.camera);
    nlohmann::json report = nlohmann::json::parse(geometry.report_json);
    report["texture"] = texture_file.lexically_relative(run.folder).string();
    report["color"] = kRgbdColorSource;
    report["seconds"]["color"] = std::chrono::duration<double>(Clock::now() - start).count();
    WriteRgbdColour(files, color, geometry.points, PointColours(geometry.points, camera, color),
                    report.dump(2) + "\n");
  } catch (const FileError& e) {
    FailAcquisition(result, e.path(), e.what());
    return result;
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace sewer3d
