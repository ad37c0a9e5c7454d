// The RGB-D stage's seam pass: the modules' relative colour gains from the wall neighbouring
// modules see at the same counter (texture/module_gains.hpp; rgbd_colour.hpp).

#include <algorithm>
#include <map>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/reference_light_io.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/pipeline/acquisition_images.hpp"
#include "sewer3d/pipeline/rgbd_colour.hpp"
#include "sewer3d/texture/depth_prior.hpp"

namespace sewer3d {
namespace {

struct SeamImage {
  cv::Mat3f colour;  // corrected by its own module's reference, smoothed
  cv::Mat1f depth;   // as measured (no prior: only the wall both measured is compared)
  double distance_mm = 0.0;
};

std::optional<SeamImage> ReadSeamImage(const CaptureRun& run, const Acquisition& a,
                                       const std::filesystem::path& rgbd_folder,
                                       const ShadingCorrector& corrector) {
  const RgbdFiles files = RgbdAcquisitionFiles(rgbd_folder, a.module, a.counter);
  const int pattern = a.Image(ImageKind::kPattern);
  if (!RgbdGeometryDone(files) || pattern < 0 || a.Image(ImageKind::kTextureBefore) < 0)
    return std::nullopt;
  const auto distance = OdometryDistanceAt(run.odometry, run.images[pattern].time_s);
  if (!distance) return std::nullopt;
  try {
    SeamImage s;
    s.depth = ReadRgbdGeometry(files).depth_mm;
    const cv::Mat3f linear = ReadLinearTexture(run, a, ImageKind::kTextureBefore);
    // Colour is compared over regions: 9 px of box mean hide the ~0.5 mm between texture and
    // pattern instants and the fine texture.
    cv::blur(corrector.Correct(linear, s.depth).linear_bgr, s.colour, cv::Size(9, 9));
    s.distance_mm = *distance;
    return s;
  } catch (const FileError&) {
    return std::nullopt;  // the colour pass reports the acquisition
  }
}

// b's camera from a's: the carrier moved along its axis by the odometry between the two
// pattern instants (odd modules fire later).
Rigid3d BFromA(const CaptureRun& run, int a, int b, double moved_mm) {
  const Rigid3d carrier_shift(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, -moved_mm));
  return run.rig.modules[b].carrier_from_camera.Inverse() * carrier_shift *
         run.rig.modules[a].carrier_from_camera;
}

}  // namespace

ModuleGains RgbdSeamPass(const CaptureRun& run, const std::vector<Acquisition>& acquisitions,
                         const std::filesystem::path& rgbd_folder,
                         const std::vector<const ShadingCorrector*>& correctors,
                         const RgbdColourOptions& options) {
  const int modules = static_cast<int>(run.rig.modules.size());
  const std::filesystem::path file = rgbd_folder / "reference" / "module_gains.json";
  if (IsRegularFile(file)) return ReadModuleGains(file, modules);
  std::map<std::pair<int, int>, const Acquisition*> by_key;
  int last_counter = -1;
  for (const Acquisition& a : acquisitions) {
    by_key[{a.module, a.counter}] = &a;
    last_counter = std::max(last_counter, a.counter);
  }
  std::vector<SeamMeasurement> seams;
  const int counters = std::min(options.seam_counters, last_counter + 1);
  for (int k = 0; k < counters && modules > 1; ++k) {
    const int counter = (2 * k + 1) * (last_counter + 1) / (2 * counters);
    for (int a = 0; a < modules; ++a) {
      const int b = (a + 1) % modules;
      if (b == a || !correctors[a] || !correctors[b]) continue;
      const auto ia = by_key.find({a, counter}), ib = by_key.find({b, counter});
      if (ia == by_key.end() || ib == by_key.end()) continue;
      const auto sa = ReadSeamImage(run, *ia->second, rgbd_folder, *correctors[a]);
      const auto sb = ReadSeamImage(run, *ib->second, rgbd_folder, *correctors[b]);
      if (!sa || !sb) continue;
      const auto ratio =
          MeasureSeamRatio(sa->colour, sa->depth, CameraModel(run.rig.modules[a].module.camera),
                           sb->colour, sb->depth, CameraModel(run.rig.modules[b].module.camera),
                           BFromA(run, a, b, sb->distance_mm - sa->distance_mm), options.seams);
      if (ratio) seams.push_back({a, b, *ratio});
    }
  }
  ModuleGains gains = SolveModuleGains(modules, seams);
  WriteModuleGains(file, gains);
  return gains;
}

}  // namespace sewer3d
