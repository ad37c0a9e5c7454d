#include "sewer3d/triangulate/reconstruct_frame.hpp"

#include <chrono>
#include <cmath>
#include <opencv2/core.hpp>
#include <string>
#include <utility>

#include "sewer3d/core/check.hpp"
#include "sewer3d/triangulate/depth_map.hpp"

namespace sewer3d {
namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

const FrameReconstructionOptions& Checked(const FrameReconstructionOptions& options) {
  options.Check();
  return options;
}

}  // namespace

void FrameReconstructionOptions::Check() const {
  decoder.niblack.Check();
  decoder.spots.Check();
  decoder.lattice.Check();
  triangulation.Check();
  outliers.Check();
  cut_spots.Check();
  lost_spots.Check();
  ValidatePositive("max_edge_steps", max_edge_steps);
  for (const auto& [field, value] :
       {std::pair{"mismatch_off_epipolar_fraction", mismatch_off_epipolar_fraction},
        std::pair{"mismatch_window_fraction", mismatch_window_fraction}})
    SEWER3D_VALIDATE(value >= 0.0 && value <= 1.0, field, "must be 0..1, got " << value);
  SEWER3D_VALIDATE(mismatch_min_decoded >= 1, "mismatch_min_decoded",
                   "must be >= 1, got " << mismatch_min_decoded);
}

std::string NotOfModuleReason(const FrameReport& r) {
  return std::to_string(r.rejected.no_tile_on_epipolar_line) + " of " +
         std::to_string(r.spots_decoded) +
         " decoded spots fit no tile on their epipolar line and " +
         std::to_string(r.windows_decoded) + " of " + std::to_string(r.windows_read) +
         " windows decode: the image is mirrored or flipped, or not of this module's pattern";
}

std::string NoPointsReason(const FrameReport& r) {
  const std::string counts = std::to_string(r.spots_found) + " spots found, " +
                             std::to_string(r.spots_decoded) + " decoded";
  if (r.spots_decoded == 0) return "no spot pattern decoded (" + counts + ")";
  const FrameReport::Rejected& x = r.rejected;
  return counts + ", none gave a point (" + std::to_string(x.no_tile_on_epipolar_line) +
         " fit no tile on their epipolar line, " + std::to_string(x.several_tiles_fit) +
         " several, " + std::to_string(x.depth_outlier_or_isolated) +
         " depth outliers or isolated): is the image shifted, rotated or scaled against the "
         "module's calibration, or of another module?";
}

std::string FrameDoubt(const FrameReport& r, std::size_t points) {
  if (points >= 3 && r.depth_pixels == 0) {
    return std::to_string(points) +
           " points but an empty depth map: every triangle between them is longer than the "
           "longest edge allowed (max_edge_steps, --max-edge-steps)";
  }
  if (r.spots_found >= 50 && 2 * r.spots_decoded < r.spots_found) {
    return std::to_string(r.spots_decoded) + " of " + std::to_string(r.spots_found) +
           " spots decoded: the spots may be too small or too close together for the camera "
           "(sewer3d describe checks a module)";
  }
  if (r.spots_decoded > 0 && 2 * points < static_cast<std::size_t>(r.spots_decoded)) {
    return std::to_string(points) + " of " + std::to_string(r.spots_decoded) +
           " decoded spots gave a point (the others' disparities lie outside the module's "
           "working range): is the image of this module?";
  }
  return {};
}

FrameReconstructor::FrameReconstructor(const ModuleDescription& module, const BinaryArray& pattern,
                                       const PatternConstraints& constraints,
                                       const FrameReconstructionOptions& options)
    : module_(module),
      options_(Checked(options)),
      decoder_(module, pattern, constraints, options.decoder),
      triangulator_(module, pattern.rows, pattern.cols, options.triangulation),
      mesh_(MeshLitElements(module, pattern)),
      mesh_neighbours_(MeshNeighbours(mesh_)),
      lost_spots_(mesh_, pattern.rows, pattern.cols, options.lost_spots) {}

FrameReconstruction FrameReconstructor::Reconstruct(const cv::Mat& pattern_image,
                                                    const cv::Mat3b* texture_bgr) {
  SEWER3D_VALIDATE(pattern_image.type() == CV_8UC1 || pattern_image.type() == CV_16UC1,
                   "pattern image", "must be 8- or 16-bit grey");
  SEWER3D_VALIDATE(!texture_bgr || texture_bgr->size() == pattern_image.size(), "texture",
                   "size differs from the pattern image");
  const DecodeResult decoded = decoder_.Decode(pattern_image);
  std::vector<CodedObservation> observations = CodedObservations(decoded);
  FrameReconstruction frame;
  FrameReport& report = frame.report;
  auto t = Clock::now();
  TriangulationStats stats;
  std::vector<TriangulatedPoint> points = triangulator_.Triangulate(observations, &stats);
  const InconsistentPoints removed =
      RejectInconsistentPoints(points, observations, options_.outliers);
  report.rejected.depth_outlier_or_isolated = removed.depth_outliers;
  report.rejected.element_claimed_twice = removed.shared_elements;
  spot_areas_.clear();
  for (const SpotCode& c : decoded.codes) spot_areas_.push_back(decoded.spots[c.spot].area_px);
  report.rejected.cut_by_step =
      RejectCutSpots(points, observations, spot_areas_, mesh_, mesh_neighbours_, stats.tolerance_px,
                     options_.cut_spots);
  const auto decoded_spots = static_cast<double>(decoded.codes.size());
  if (decoded_spots >= options_.mismatch_min_decoded &&
      stats.no_element > options_.mismatch_off_epipolar_fraction * decoded_spots &&
      decoded.stats.windows_decoded <
          options_.mismatch_window_fraction * decoded.stats.windows_read) {
    report.not_of_module = true;
    report.rejected.not_of_module = static_cast<int>(points.size());
    points.clear();
  }
  report.seconds.triangulate = Since(t);
  t = Clock::now();
  report.lost_spots_found = lost_spots_.Find(pattern_image, decoded.spots, triangulator_,
                                             stats.tolerance_px, observations, points);
  report.seconds.lost_spots = Since(t);
  t = Clock::now();
  frame.coloured = texture_bgr != nullptr;
  frame.points.reserve(points.size());
  pixels_.clear();
  depths_.clear();
  elements_.clear();
  for (const TriangulatedPoint& p : points) {
    FramePoint& out = frame.points.emplace_back();
    out.point_mm = p.point_mm;
    out.camera_px = observations[p.observation].camera_px;
    out.row = p.row;
    out.col = p.col;
    if (texture_bgr) {  // the nearest pixel: spots are a few pixels wide, colour varies slowly
      const cv::Vec3b bgr = (*texture_bgr)(static_cast<int>(std::lround(out.camera_px.y())),
                                           static_cast<int>(std::lround(out.camera_px.x())));
      out.rgb = {bgr[2], bgr[1], bgr[0]};
    }
    pixels_.push_back(out.camera_px);
    depths_.push_back(out.point_mm.z());
    elements_.emplace_back(out.row, out.col);
  }
  const double max_edge_px = options_.max_edge_steps * module_.pattern.pitch_px;
  frame.depth_mm =
      options_.bridge_lost_spots
          ? InterpolateDepth(pattern_image.size(), pixels_, depths_, max_edge_px)
          : InterpolateDepthOnMesh(pattern_image.size(), mesh_, elements_, pixels_, depths_,
                                   {.max_edge_px = max_edge_px,
                                    .spot_radius_px = 0.25 * module_.pattern.pitch_px,
                                    .holes_to_midpoints = options_.holes_to_midpoints});
  report.seconds.depth_map = Since(t);
  report.depth_pixels = CountDepthPixels(frame.depth_mm);

  report.spots_found = static_cast<int>(decoded.spots.size());
  report.lattice_groups = decoded.lattice.groups;
  report.lattice_conflicts = decoded.lattice.conflicts;
  report.windows_read = decoded.stats.windows_read;
  report.windows_decoded = decoded.stats.windows_decoded;
  report.bits_corrected = decoded.stats.bits_corrected;
  report.spots_decoded = static_cast<int>(decoded.codes.size());
  report.rejected.votes_split_or_too_few = decoded.stats.spots_ambiguous;
  report.rejected.beyond_lens_fold = stats.unprojectable;
  report.rejected.no_tile_on_epipolar_line = stats.no_element;
  report.epipolar_tolerance_px = stats.tolerance_px;
  report.rejected.several_tiles_fit = stats.ambiguous;
  report.points = static_cast<int>(frame.points.size());
  report.seconds.binarise = decoded.seconds_binarise;
  report.seconds.spots = decoded.seconds_spots;
  report.seconds.lattice = decoded.seconds_lattice;
  report.seconds.codewords = decoded.seconds_codewords;
  return frame;
}

FrameReconstruction ReconstructFrame(const ModuleDescription& module, const BinaryArray& pattern,
                                     const PatternConstraints& constraints,
                                     const cv::Mat& pattern_image, const cv::Mat3b* texture_bgr,
                                     const FrameReconstructionOptions& options) {
  return FrameReconstructor(module, pattern, constraints, options)
      .Reconstruct(pattern_image, texture_bgr);
}

}  // namespace sewer3d
