#include "sewer3d/pipeline/rgbd_colour.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/pipeline/acquisition_images.hpp"
#include "sewer3d/pipeline/rgbd_inputs.hpp"
#include "sewer3d/texture/colour.hpp"
#include "sewer3d/texture/depth_prior.hpp"

namespace sewer3d {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

// The wall's diameter seen by this frame: twice the median distance of its points from the
// carrier axis (carrier z); the nominal diameter when it has too few points.
double WallDiameterMm(const std::vector<Eigen::Vector3d>& points,
                      const Rigid3d& carrier_from_camera, double nominal_mm) {
  if (points.size() < 50) return nominal_mm;
  std::vector<double> rho;
  rho.reserve(points.size());
  for (const Eigen::Vector3d& p : points) rho.push_back((carrier_from_camera * p).head<2>().norm());
  std::nth_element(rho.begin(), rho.begin() + rho.size() / 2, rho.end());
  return 2.0 * rho[rho.size() / 2];
}

// The camera's velocity (mm/s, camera frame) at `time_s`: the odometry's speed along the carrier
// axis (+z forward) over ±50 ms (one reading interval of a 20 Hz counter), clamped to the
// readings' span; nullopt without two readings around.
std::optional<Eigen::Vector3d> CameraVelocity(const CaptureRun& run,
                                              const Rigid3d& carrier_from_camera, double time_s) {
  constexpr double kHalfWindowS = 0.05;
  if (run.odometry.size() < 2) return std::nullopt;
  const double t0 = std::max(time_s - kHalfWindowS, run.odometry.front().time_s);
  const double t1 = std::min(time_s + kHalfWindowS, run.odometry.back().time_s);
  if (t1 - t0 < 0.01) return std::nullopt;
  const auto d0 = OdometryDistanceAt(run.odometry, t0);
  const auto d1 = OdometryDistanceAt(run.odometry, t1);
  if (!d0 || !d1) return std::nullopt;
  const double speed = (*d1 - *d0) / (t1 - t0);
  return carrier_from_camera.rotation.conjugate() * Eigen::Vector3d(0, 0, speed);
}

json DeblurJson(const DeblurReport& r) {
  return {{"along_columns", r.along_columns},
          {"off_axis_deg", r.off_axis_deg},
          {"min_length_px", r.min_length_px},
          {"max_length_px", r.max_length_px},
          {"bins", r.bins},
          {"pixels_restored", r.pixels_restored},
          {"pixels_clamped", r.pixels_clamped},
          {"noise_sigma", r.noise_sigma},
          {"noise_to_signal", r.noise_to_signal},
          {"ms", r.time_ms}};
}

json MappingJson(const TripletMappingReport& r) {
  return {{"method", r.method},
          {"features_before", r.features_before},
          {"features_after", r.features_after},
          {"matches", r.matches},
          {"inliers", r.inliers},
          {"reprojection_rms_px", r.reprojection_rms_px},
          {"motion_mm", r.motion_mm},
          {"rotation_deg", r.rotation_deg},
          {"mapped_pixels", r.mapped_pixels},
          {"ms", r.time_ms}};
}

// The cloud's colours: the colour image at each point's projection (nearest pixel).
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

// Debug pictures of one acquisition (RgbdColourOptions::debug_images).
void WriteDebugImages(const std::filesystem::path& rgbd_folder, const Acquisition& a,
                      const cv::Mat3f& captured, const cv::Mat3f& deblurred,
                      const cv::Mat3f& mapped) {
  const std::filesystem::path folder = rgbd_folder / "debug" / fmt::format("m{}", a.module);
  auto write = [&](const std::string& name, const cv::Mat& image) {
    WriteFileAtomically(folder / fmt::format("{:06d}_{}", a.counter, name),
                        [&](const auto& t) { WriteImage(t, image); });
  };
  // Shown with one gain so that the brightest percent is white.
  cv::Mat1f grey;
  cv::cvtColor(captured, grey, cv::COLOR_BGR2GRAY);
  std::vector<float> values(grey.begin(), grey.end());
  std::nth_element(values.begin(), values.begin() + values.size() * 99 / 100, values.end());
  const double gain = 1.0 / std::max(1e-3f, values[values.size() * 99 / 100]);
  write("captured.png", Srgb8FromLinear(captured * gain));
  write("mapped.png", Srgb8FromLinear(mapped * gain));
  const int side = std::min({160, captured.cols, captured.rows});
  const cv::Rect crop((captured.cols - side) / 2, (captured.rows - side) / 2, side, side);
  cv::Mat pair, big;
  cv::hconcat(std::vector<cv::Mat>{Srgb8FromLinear(captured(crop) * gain),
                                   Srgb8FromLinear(deblurred(crop) * gain)},
              pair);
  cv::resize(pair, big, cv::Size(), 3, 3, cv::INTER_NEAREST);
  write("deblur_crop.png", big);
}

}  // namespace

void RgbdColourOptions::Check() const {
  SEWER3D_VALIDATE(reference_frames >= 1, "reference_frames",
                   "must be at least 1, got " << reference_frames);
  reference.Check();
  deblurring.Check();
  mapping.Check();
  correction.Check();
  SEWER3D_VALIDATE(seam_counters >= 1, "seam_counters",
                   "must be at least 1, got " << seam_counters);
  seams.Check();
  ValidatePositive("nominal_diameter_mm", nominal_diameter_mm);
}

std::string RgbdColourOptionsJson(const RgbdColourOptions& o) {
  const json j = {{"reference_frames", o.reference_frames},
                  {"deblur", o.deblur},
                  {"deblur_max_gain", o.deblurring.max_gain},
                  {"mapping_min_inliers", o.mapping.min_inliers},
                  {"correction", o.correction.space == CorrectionSpace::kLab ? "lab" : "linear"},
                  {"wall_level_linear", o.correction.wall_level_linear},
                  {"nominal_diameter_mm", o.nominal_diameter_mm},
                  {"seam_counters", o.seam_counters}};
  return j.dump();
}

RgbdAcquisitionResult RgbdColourPass(const CaptureRun& run, const Acquisition& a,
                                     const std::filesystem::path& rgbd_folder,
                                     const ShadingCorrector* corrector,
                                     const cv::Vec3d& module_gain,
                                     const RgbdColourOptions& options) {
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
  if (corrector == nullptr) {
    FailAcquisition(result, rgbd_folder / "reference",
                    "module m" + std::to_string(a.module) + " has no reference light");
    return result;
  }
  const auto start = Clock::now();
  try {
    const RgbdGeometry geometry = ReadRgbdGeometry(files);
    const cv::Mat3f before = ReadLinearTexture(run, a, ImageKind::kTextureBefore);
    const cv::Mat3f after = ReadLinearTexture(run, a, ImageKind::kTextureAfter);
    for (const auto& [image, kind] : {std::pair{&before, ImageKind::kTextureBefore},
                                      std::pair{&after, ImageKind::kTextureAfter}}) {
      const std::string problem = ExposureProblem(*image);
      if (!problem.empty())
        result.warnings.push_back(AcquisitionImageFile(run, a, kind).string() + ": " + problem);
    }
    const RigModule& m = run.rig.modules.at(a.module);
    const CameraModel camera(m.module.camera);
    const double diameter =
        WallDiameterMm(geometry.points, m.carrier_from_camera, options.nominal_diameter_mm);
    const cv::Mat1f depth = FillDepthFromPrior(
        geometry.depth_mm,
        PipePriorDepth(corrector->normalised(), m.carrier_from_camera, diameter));
    const RunImage& before_image = run.images[a.Image(ImageKind::kTextureBefore)];
    const RunImage& pattern_image = run.images[a.Image(ImageKind::kPattern)];
    const RunImage& after_image = run.images[a.Image(ImageKind::kTextureAfter)];
    const auto velocity = CameraVelocity(run, m.carrier_from_camera, pattern_image.time_s);
    json texture = {{"wall_diameter_mm", diameter}, {"odometry_speed_mm_s", nullptr}};
    if (velocity) texture["odometry_speed_mm_s"] = velocity->norm();
    cv::Mat3f before_sharp = before, after_sharp = after;
    if (options.deblur && velocity) {
      const DeblurResult b =
          Deblur(before, depth, camera, *velocity, before_image.exposure_ms, options.deblurring);
      const DeblurResult c =
          Deblur(after, depth, camera, *velocity, after_image.exposure_ms, options.deblurring);
      before_sharp = b.image;
      after_sharp = c.image;
      texture["deblur"] = DeblurJson(b.report);
    } else {
      texture["deblur"] = options.deblur ? "not done: no odometry at this time" : "off";
    }
    const TripletMappingResult mapped = MapTripletToPattern(
        before_sharp, after_sharp, depth, camera,
        {before_image.time_s, pattern_image.time_s, after_image.time_s}, velocity, options.mapping);
    texture["mapping"] = MappingJson(mapped.report);
    const CorrectedTexture corrected = corrector->Correct(mapped.color, depth);
    texture["correction"] = {{"pixels_corrected", corrected.report.pixels_corrected},
                             {"pixels_without_depth", corrected.report.pixels_without_depth}};
    const cv::Mat3b color = Srgb8FromLinear(ApplyChannelGains(
        corrected.linear_bgr, {1.0 / module_gain[0], 1.0 / module_gain[1], 1.0 / module_gain[2]}));
    if (options.debug_images) WriteDebugImages(rgbd_folder, a, before, before_sharp, mapped.color);
    json report = json::parse(geometry.report_json);
    report["texture"] = AcquisitionImageFile(run, a, ImageKind::kTextureBefore)
                            .lexically_relative(run.folder)
                            .string();
    report["color"] = RgbdColorSource(options);
    report["color_steps"] = texture;
    for (const std::string& w : result.warnings) report["warnings"].push_back(w);
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

std::string RgbdColorSource(const RgbdColourOptions& options, const std::string& deblur_note) {
  const std::string deblur =
      !options.deblur ? "not deblurred"
                      : "deblurred" + (deblur_note.empty() ? "" : " (" + deblur_note + ")");
  return "texture triplet: " + deblur +
         ", mapped to the pattern instant, shading and colour corrected" +
         (options.correction.space == CorrectionSpace::kLab ? " (in Lab)" : "");
}

}  // namespace sewer3d
