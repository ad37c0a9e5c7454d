#pragma once
/// \file
/// Shading and colour correction of the texture images (paper §3.2; docs/texture.md,
/// "Shading and colour correction").
///
/// Model: a texture pixel p of module m, linear BGR per channel c,
///   observed_c(p) = albedo_c(X) · L_m,c(p) · G(p),   G(p) = cos(incidence) · (d_ref / d)²,
/// with X the wall point seen at p, d = |X| its distance from the camera centre (the ring light
/// sits there), incidence the angle between the ray and the wall normal (from the depth map's
/// gradients), and L_m,c(p) everything fixed in the image of the module: the ring light's
/// emission pattern and colour over the emission angle, lens vignetting per channel, white
/// balance and exposure. The **reference light** R_m,c(p) = ā_m,c · L_m,c(p) is estimated from
/// the run's own texture images, without a white target: over many frames the wall seen at a
/// pixel changes, so the median over frames of observed / G at p is L_m(p) times the median
/// albedo ā_m of the walls module m saw — which no target-free method can separate from L_m.
/// The correction divides it out, so the run's median wall becomes a neutral grey of the
/// chosen level in every module (same-median-wall assumption, docs/texture.md).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "sewer3d/camera/camera_model.hpp"

namespace sewer3d {

/// How G(p) is computed from a depth map.
struct GeometryOptions {
  double reference_distance_mm = 150.0;  ///< d_ref: G = 1 at this distance, normal incidence
  int normal_step_px = 2;                ///< half-width of the differences giving the normal
  double min_cos_incidence = 0.25;       ///< more grazing pixels: not estimated from; clamped here
  void Check() const;
};

/// Normalised undistorted coordinates (x, y at Z = 1) of every pixel of the camera; NaN beyond
/// the fold of the distortion polynomial. Computing it is the costly part of G, so the
/// estimator and the corrector compute it once.
cv::Mat2f NormalisedCoordinates(const CameraModel& camera);

/// G(p) = cos(incidence) · (d_ref / d)² for a depth map z(u, v) (mm along the optical axis,
/// NaN = unknown) of the camera whose NormalisedCoordinates are given; cos(incidence) is
/// clamped below at min_cos_incidence. NaN where the depth, its neighbours for the normal, or
/// the ray are unknown. Throws std::invalid_argument when the sizes differ.
cv::Mat1f GeometricFactor(const cv::Mat1f& depth_mm, const cv::Mat2f& normalised,
                          const GeometryOptions& options);

/// The estimated reference light of one module: R_c(p) = level_c · shape_c(p), linear BGR of a
/// wall of the run's median albedo seen at d_ref at normal incidence.
struct ReferenceLight {
  cv::Size image_size;
  int grid_cols = 0, grid_rows = 0;  ///< cell (i, j) covers columns [i W / cols, (i+1) W / cols)
  /// log2 R_c at each cell centre, row-major (grid_rows × grid_cols), BGR.
  std::vector<cv::Vec3f> log2_bgr;
  /// The overall level: geometric mean of R over the cells, BGR. It holds the unknown median
  /// albedo of the walls, the ring light's power, the exposure and the white balance.
  cv::Vec3d level_bgr{0.0, 0.0, 0.0};
  GeometryOptions geometry;  ///< how G was computed; the correction uses the same

  /// R(p) (linear BGR) at a pixel: bilinear between cell centres in log2, extrapolated
  /// linearly beyond the outermost centres.
  cv::Vec3d At(double u_px, double v_px) const;
  /// R at every pixel of the image.
  cv::Mat3f Render() const;
};

struct ReferenceLightOptions {
  int grid_cols = 64, grid_rows = 48;  ///< coarse grid of the statistics
  /// A cell spans at least this many pixels each way: a small image gets fewer cells (a 320 px
  /// camera 32 x 24), so that one frame gives a cell min_samples_per_cell samples.
  int min_cell_px = 10;
  /// Histogram of log2(observed / G) per cell and channel: bins of 1/bins_per_stop stop over
  /// [log2_min, log2_max); values outside count in an under- or overflow bin.
  int bins_per_stop = 16;
  double log2_min = -12.0, log2_max = 4.0;
  /// Observed linear values below dark_linear or above saturated_linear are censored: they
  /// count below / above every bin, which leaves the median exact while they are a minority.
  double dark_linear = 0.002, saturated_linear = 0.95;
  int min_samples_per_cell = 100;  ///< fewer: the cell is filled from its neighbours
  /// Half-width (cells) of the local quadratic fit smoothing the log grid; 0 = none.
  int smoothing_cells = 3;
  /// > 0: per channel, the cells are replaced by a robust polynomial fit of this total degree
  /// over the image (light_model.hpp) instead of hole filling and local smoothing: the light is
  /// smooth, while the wall content a short or mixed run leaves in the per-cell medians is not.
  int model_degree = 4;
  /// Per cell, the mean of log2(observed / G) between the trim and 1 − trim quantiles of its
  /// frames' values (0.5: the median). 0.25 keeps the median's robustness to spots and pores
  /// but moves continuously when a cell's frames mix walls of two materials.
  double trim_fraction = 0.25;
  GeometryOptions geometry;
  void Check() const;
};

struct ReferenceLightReport {
  int frames = 0;
  std::int64_t samples_used = 0;             ///< pixels counted (censored ones included)
  std::int64_t samples_censored = 0;         ///< channel values below dark or above saturated
  std::int64_t pixels_without_geometry = 0;  ///< depth, normal or ray unknown
  std::int64_t pixels_grazing = 0;           ///< cos(incidence) < min_cos_incidence
  int cells = 0;                             ///< grid cells × 3 channels
  int cells_filled = 0;  ///< of those, filled from neighbours (too few samples / censored)
};

struct ReferenceLightResult {
  std::optional<ReferenceLight> reference;  ///< nullopt when no cell has enough samples
  ReferenceLightReport report;
};

/// Accumulates the texture frames of one module. Memory is fixed at construction (the
/// histograms and the camera's normalised coordinates) and does not grow with frames.
class ReferenceLightEstimator {
 public:
  ReferenceLightEstimator(const CameraModel& camera, const ReferenceLightOptions& options);
  /// Adds one frame: linear BGR texture and its depth map (same size as the camera image;
  /// throws std::invalid_argument otherwise). Pixels with NaN depth are skipped.
  void Add(const cv::Mat3f& linear_bgr, const cv::Mat1f& depth_mm);
  /// The reference from the frames so far (per-cell medians, filled and smoothed).
  ReferenceLightResult Estimate() const;
  /// Bytes held by the accumulated statistics and caches.
  std::size_t memory_bytes() const;

 private:
  int Bins() const {
    return static_cast<int>((options_.log2_max - options_.log2_min) * options_.bins_per_stop) + 2;
  }
  ReferenceLightOptions options_;
  cv::Size size_;
  cv::Mat2f normalised_;
  std::vector<std::uint32_t> histograms_;  ///< [cell][channel][bin], bin 0 / last = under/over
  ReferenceLightReport report_;
};

/// How the correction combines observation and reference.
enum class CorrectionSpace {
  kLab,  ///< the paper's: L* from the luminance ratio, the reference's a*/b* cast removed
  /// Per-channel division in linear RGB (von Kries). The default: the cast is removed as a
  /// gain, so walls of another colour than the reference's keep their colour; the Lab form
  /// removes it as an a*/b* offset, which tints them (docs/texture.md, measured).
  kLinear,
};

struct CorrectionOptions {
  CorrectionSpace space = CorrectionSpace::kLinear;
  /// Linear grey level to which the run's median wall is mapped, common to all modules.
  double wall_level_linear = 0.2;
  /// The colour (linear BGR) the run's median wall is given instead of that grey, the same for
  /// every module; all zero: the grey. The RGB-D stage passes the modules' mean reference level
  /// scaled to wall_level_linear's luminance (CommonWallColour), so that the run's own wall
  /// colour (e.g. a clay pipe's) is kept and only what differs between modules is removed.
  cv::Vec3d target_bgr{0.0, 0.0, 0.0};
  void Check() const;
};

/// The colour the median wall of every module is mapped to: the geometric mean of the
/// modules' reference levels (ReferenceLight::level_bgr), scaled to the luminance of
/// `wall_level_linear`. Under the assumption that the modules saw the same walls over the run,
/// their levels differ only by each camera's white balance and light, and the mean keeps the
/// walls' colour. Throws std::invalid_argument when `levels_bgr` is empty or not positive.
cv::Vec3d CommonWallColour(const std::vector<cv::Vec3d>& levels_bgr, double wall_level_linear);

struct CorrectionReport {
  int pixels_corrected = 0;      ///< depth known: shading, falloff and cast removed
  int pixels_without_depth = 0;  ///< corrected by the reference light only (G = 1), unmarked
};

struct CorrectedTexture {
  cv::Mat3f linear_bgr;  ///< corrected linear BGR (may exceed 1)
  cv::Mat1b full_mask;   ///< 255 where the depth was known (full correction), else 0
  CorrectionReport report;
};

/// Corrects the texture images of one module with its reference light.
class ShadingCorrector {
 public:
  ShadingCorrector(const CameraModel& camera, const ReferenceLight& reference,
                   const CorrectionOptions& options);
  /// Corrects one frame. The depth must be finite wherever the full correction is wanted (the
  /// caller fills the decoder's holes with a pipe prior first); NaN-depth pixels get G = 1.
  /// Throws std::invalid_argument when the sizes differ from the camera's.
  CorrectedTexture Correct(const cv::Mat3f& linear_bgr, const cv::Mat1f& depth_mm) const;
  /// The same on an 8-bit sRGB BGR texture, returning 8-bit sRGB (clipped).
  cv::Mat3b CorrectSrgb8(const cv::Mat3b& srgb_bgr, const cv::Mat1f& depth_mm) const;
  /// The camera's NormalisedCoordinates, for callers that need them too (e.g. the pipe prior).
  const cv::Mat2f& normalised() const { return normalised_; }

 private:
  CorrectionOptions options_;
  GeometryOptions geometry_;
  cv::Mat2f normalised_;
  cv::Mat3f reference_bgr_;
};

}  // namespace sewer3d
