// The RGB-D stage's reference pass: one reference light per module (rgbd_colour.hpp).

#include <fmt/core.h>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/reference_light_io.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/pipeline/acquisition_images.hpp"
#include "sewer3d/pipeline/rgbd_colour.hpp"
#include "sewer3d/texture/colour.hpp"
#include "sewer3d/triangulate/depth_map.hpp"

namespace sewer3d {
namespace {

std::filesystem::path ReferenceFile(const std::filesystem::path& rgbd_folder, int module,
                                    const char* extension) {
  return rgbd_folder / "reference" / fmt::format("m{}{}", module, extension);
}

nlohmann::json ReportJson(const ReferenceLightReport& r) {
  return {{"frames", r.frames},
          {"samples_used", r.samples_used},
          {"samples_censored", r.samples_censored},
          {"pixels_without_geometry", r.pixels_without_geometry},
          {"pixels_grazing", r.pixels_grazing},
          {"cells", r.cells},
          {"cells_filled", r.cells_filled}};
}

// The reference for people: its shape, brightest point white, as sRGB.
cv::Mat3b ReferencePicture(const ReferenceLight& reference) {
  cv::Mat3f shape = reference.Render();
  double top = 0;
  cv::minMaxLoc(shape.reshape(1), nullptr, &top);
  if (top > 0) shape /= top;
  return Srgb8FromLinear(shape);
}

}  // namespace

RgbdReferenceResult RgbdReferencePass(const CaptureRun& run, int module,
                                      const std::vector<Acquisition>& acquisitions,
                                      const std::filesystem::path& rgbd_folder,
                                      const RgbdColourOptions& options) {
  RgbdReferenceResult result;
  result.module = module;
  const std::filesystem::path file = ReferenceFile(rgbd_folder, module, ".json");
  if (IsRegularFile(file)) {
    result.reference = ReadReferenceLight(file);
    result.skipped = true;
    return result;
  }
  std::vector<const Acquisition*> usable;
  for (const Acquisition& a : acquisitions) {
    if (a.module == module && a.Image(ImageKind::kTextureBefore) >= 0 &&
        RgbdGeometryDone(RgbdAcquisitionFiles(rgbd_folder, a.module, a.counter)))
      usable.push_back(&a);
  }
  const CameraModel camera(run.rig.modules.at(module).module.camera);
  ReferenceLightEstimator estimator(camera, options.reference);
  const int n = std::min<int>(options.reference_frames, static_cast<int>(usable.size()));
  std::string unreadable;  // the first image that could not be read
  int without_depth = 0;   // read, but no pixel of depth
  int without_points = 0;  // read, but not one point (nothing decoded)
  for (int k = 0; k < n; ++k) {
    const Acquisition& a = *usable[(2 * k + 1) * usable.size() / (2 * n)];
    try {
      const cv::Mat3f linear = ReadLinearTexture(run, a, ImageKind::kTextureBefore);
      const RgbdGeometry geometry =
          ReadRgbdGeometry(RgbdAcquisitionFiles(rgbd_folder, a.module, a.counter));
      estimator.Add(linear, geometry.depth_mm);
      without_depth += CountDepthPixels(geometry.depth_mm) == 0 ? 1 : 0;
      without_points += geometry.points.empty() ? 1 : 0;
    } catch (const FileError& e) {
      // Passed over here; the colour pass fails the acquisition with the file and reason.
      if (unreadable.empty()) unreadable = e.what();
    }
  }
  const ReferenceLightResult estimate = estimator.Estimate();
  result.report = estimate.report;
  result.reference = estimate.reference;
  if (!result.reference) {
    result.file = file.string();
    if (!unreadable.empty()) {
      result.reason = "no reference light: a texture image could not be read (" + unreadable + ")";
    } else if (n > 0 && without_points == n) {
      result.reason = "no reference light: the module's " + std::to_string(n) +
                      " acquisitions read have not one point (no spot pattern decoded: are the "
                      "pattern images blank, blown out or of another module? see the geometry "
                      "reports)";
    } else if (n > 0 && without_depth == n) {
      result.reason = "no reference light: the depth maps of the module's " + std::to_string(n) +
                      " acquisitions read are empty (every triangle between their points is "
                      "longer than the longest edge allowed: max_edge_steps, --max-edge-steps)";
    } else {
      result.reason = "no reference light: none of the module's " + std::to_string(usable.size()) +
                      " acquisitions with depth gave enough samples of the wall (too few decoded "
                      "points; see the geometry reports)";
    }
    return result;
  }
  WriteFileAtomically(ReferenceFile(rgbd_folder, module, ".png"),
                      [&](const auto& t) { WriteImage(t, ReferencePicture(*result.reference)); });
  WriteReferenceLight(file, *result.reference, ReportJson(result.report).dump());
  return result;
}

}  // namespace sewer3d
