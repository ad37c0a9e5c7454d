#include "sewer3d/texture/shading.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "sewer3d/core/check.hpp"
#include "sewer3d/texture/colour.hpp"
#include "sewer3d/texture/light_model.hpp"
#include "sewer3d/texture/reference_grid.hpp"

namespace sewer3d {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

void CheckSize(cv::Size expected, cv::Size got, const char* field) {
  SEWER3D_VALIDATE(expected == got, field,
                   "size " << got.width << "x" << got.height << " differs from the camera's "
                           << expected.width << "x" << expected.height);
}

// The two factors of G: cos(incidence) (unclamped, so the estimator can skip grazing pixels)
// and (d_ref / d)²; NaN where unknown.
void ComputeGeometry(const cv::Mat1f& depth_mm, const cv::Mat2f& normalised,
                     const GeometryOptions& options, cv::Mat1f& cos_incidence, cv::Mat1f& falloff) {
  CheckSize(normalised.size(), depth_mm.size(), "depth map");
  cv::Mat3f points(depth_mm.size());
  for (int r = 0; r < points.rows; ++r) {
    for (int c = 0; c < points.cols; ++c) {
      const float z = depth_mm(r, c);
      const cv::Vec2f& xy = normalised(r, c);
      points(r, c) = z > 0.0f ? cv::Vec3f(z * xy[0], z * xy[1], z) : cv::Vec3f(kNaN, kNaN, kNaN);
    }
  }
  const auto finite = [](const cv::Vec3f& p) { return std::isfinite(p[0] + p[1]); };
  // Central difference over ±step, one-sided where a neighbour is unknown or outside.
  const auto tangent = [&](int r, int c, int dr, int dc) {
    const int s = options.normal_step_px;
    const cv::Vec3f& p = points(r, c);
    const int r0 = r - dr * s, c0 = c - dc * s, r1 = r + dr * s, c1 = c + dc * s;
    const bool has0 = r0 >= 0 && c0 >= 0 && finite(points(r0, c0));
    const bool has1 = r1 < points.rows && c1 < points.cols && finite(points(r1, c1));
    const cv::Vec3f a = has0 ? points(r0, c0) : p, b = has1 ? points(r1, c1) : p;
    return (has0 || has1) ? cv::Vec3d(b - a) : cv::Vec3d(kNaN, kNaN, kNaN);
  };
  const double d_ref2 = options.reference_distance_mm * options.reference_distance_mm;
  cos_incidence.create(depth_mm.size());
  falloff.create(depth_mm.size());
  for (int r = 0; r < points.rows; ++r) {
    for (int c = 0; c < points.cols; ++c) {
      const cv::Vec3d p = points(r, c);
      const cv::Vec3d n = finite(points(r, c)) ? tangent(r, c, 0, 1).cross(tangent(r, c, 1, 0))
                                               : cv::Vec3d(kNaN, kNaN, kNaN);
      const double d2 = p.dot(p);
      cos_incidence(r, c) = static_cast<float>(std::abs(n.dot(p)) / std::sqrt(n.dot(n) * d2));
      falloff(r, c) = static_cast<float>(d_ref2 / d2);
    }
  }
}

// Continuous cell coordinate of a pixel, split into the left cell centre and the weight of the
// right one (outside [0, 1] beyond the outermost centres: linear extrapolation).
std::pair<int, double> CellWeight(double pixel, int image_size, int cells) {
  if (cells < 2) return {0, 0.0};
  const double g = (pixel + 0.5) * cells / image_size - 0.5;
  const int i = std::clamp(static_cast<int>(std::floor(g)), 0, cells - 2);
  return {i, g - i};
}

}  // namespace

void GeometryOptions::Check() const {
  ValidatePositive("reference_distance_mm", reference_distance_mm);
  SEWER3D_VALIDATE(normal_step_px >= 1, "normal_step_px", "must be >= 1, got " << normal_step_px);
  SEWER3D_VALIDATE(min_cos_incidence > 0.0 && min_cos_incidence <= 1.0, "min_cos_incidence",
                   "must be in (0, 1], got " << min_cos_incidence);
}

void ReferenceLightOptions::Check() const {
  SEWER3D_VALIDATE(grid_cols >= 1 && grid_rows >= 1, "grid",
                   "must have at least 1 x 1 cells, got " << grid_cols << "x" << grid_rows);
  SEWER3D_VALIDATE(bins_per_stop >= 1, "bins_per_stop", "must be >= 1, got " << bins_per_stop);
  SEWER3D_VALIDATE(min_cell_px >= 1, "min_cell_px", "must be >= 1, got " << min_cell_px);
  SEWER3D_VALIDATE(log2_max > log2_min, "log2_max", "must exceed log2_min (" << log2_min << ")");
  ValidatePositive("dark_linear", dark_linear);
  SEWER3D_VALIDATE(saturated_linear > dark_linear, "saturated_linear",
                   "must exceed dark_linear (" << dark_linear << "), got " << saturated_linear);
  SEWER3D_VALIDATE(min_samples_per_cell >= 1, "min_samples_per_cell",
                   "must be >= 1, got " << min_samples_per_cell);
  ValidateNotNegative("smoothing_cells", smoothing_cells);
  SEWER3D_VALIDATE(trim_fraction > 0.0 && trim_fraction <= 0.5, "trim_fraction",
                   "must be in (0, 0.5], got " << trim_fraction);
  SEWER3D_VALIDATE(model_degree >= 0 && model_degree <= 6, "model_degree",
                   "must be 0..6, got " << model_degree);
  CheckWithin("geometry.", [&] { geometry.Check(); });
}

void CorrectionOptions::Check() const {
  ValidatePositive("wall_level_linear", wall_level_linear);
  const bool grey = target_bgr == cv::Vec3d(0, 0, 0);
  SEWER3D_VALIDATE(grey || (target_bgr[0] > 0 && target_bgr[1] > 0 && target_bgr[2] > 0),
                   "target_bgr", "must be all positive, or all zero for grey");
}

cv::Vec3d CommonWallColour(const std::vector<cv::Vec3d>& levels_bgr, double wall_level_linear) {
  SEWER3D_VALIDATE(!levels_bgr.empty(), "levels_bgr", "needs at least one module's level");
  ValidatePositive("wall_level_linear", wall_level_linear);
  cv::Vec3d log_sum(0, 0, 0);
  for (const cv::Vec3d& level : levels_bgr) {
    for (int c = 0; c < 3; ++c) {
      ValidatePositive("levels_bgr", level[c]);
      log_sum[c] += std::log(level[c]);
    }
  }
  cv::Vec3d mean;
  for (int c = 0; c < 3; ++c)
    mean[c] = std::exp(log_sum[c] / static_cast<double>(levels_bgr.size()));
  const double luminance = LinearRgbToXyz(Eigen::Vector3d(mean[2], mean[1], mean[0])).y();
  return mean * (wall_level_linear / luminance);
}

cv::Mat2f NormalisedCoordinates(const CameraModel& camera) {
  const CameraIntrinsics& in = camera.intrinsics();
  cv::Mat2f out(in.height, in.width);
  for (int r = 0; r < out.rows; ++r) {
    for (int c = 0; c < out.cols; ++c) {
      const auto xy = camera.Unproject(Eigen::Vector2d(c, r));
      out(r, c) = xy ? cv::Vec2f(static_cast<float>(xy->x()), static_cast<float>(xy->y()))
                     : cv::Vec2f(kNaN, kNaN);
    }
  }
  return out;
}

cv::Mat1f GeometricFactor(const cv::Mat1f& depth_mm, const cv::Mat2f& normalised,
                          const GeometryOptions& options) {
  options.Check();
  cv::Mat1f cos_incidence, falloff;
  ComputeGeometry(depth_mm, normalised, options, cos_incidence, falloff);
  cv::Mat1f g(depth_mm.size());
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      const float cos_i =
          std::max(cos_incidence(r, c), static_cast<float>(options.min_cos_incidence));
      g(r, c) = std::isfinite(cos_incidence(r, c)) ? cos_i * falloff(r, c) : kNaN;
    }
  }
  return g;
}

cv::Vec3d ReferenceLight::At(double u_px, double v_px) const {
  const auto [i, wx] = CellWeight(u_px, image_size.width, grid_cols);
  const auto [j, wy] = CellWeight(v_px, image_size.height, grid_rows);
  const int i1 = std::min(i + 1, grid_cols - 1), j1 = std::min(j + 1, grid_rows - 1);
  const auto cell = [&](int a, int b) { return cv::Vec3d(log2_bgr[b * grid_cols + a]); };
  const cv::Vec3d top = (1.0 - wx) * cell(i, j) + wx * cell(i1, j);
  const cv::Vec3d bottom = (1.0 - wx) * cell(i, j1) + wx * cell(i1, j1);
  const cv::Vec3d l = (1.0 - wy) * top + wy * bottom;
  return {std::exp2(l[0]), std::exp2(l[1]), std::exp2(l[2])};
}

cv::Mat3f ReferenceLight::Render() const {
  cv::Mat3f out(image_size);
  for (int r = 0; r < out.rows; ++r) {
    for (int c = 0; c < out.cols; ++c) out(r, c) = cv::Vec3f(At(c, r));
  }
  return out;
}

ReferenceLightEstimator::ReferenceLightEstimator(const CameraModel& camera,
                                                 const ReferenceLightOptions& options)
    : options_(options) {
  options_.Check();
  size_ = cv::Size(camera.intrinsics().width, camera.intrinsics().height);
  options_.grid_cols = std::clamp(size_.width / options_.min_cell_px, 1, options_.grid_cols);
  options_.grid_rows = std::clamp(size_.height / options_.min_cell_px, 1, options_.grid_rows);
  normalised_ = NormalisedCoordinates(camera);
  histograms_.assign(static_cast<size_t>(options_.grid_cols) * options_.grid_rows * 3 * Bins(), 0);
  report_.cells = options_.grid_cols * options_.grid_rows * 3;
}

void ReferenceLightEstimator::Add(const cv::Mat3f& linear_bgr, const cv::Mat1f& depth_mm) {
  CheckSize(size_, linear_bgr.size(), "texture image");
  CheckSize(size_, depth_mm.size(), "depth map");
  cv::Mat1f cos_incidence, falloff;
  ComputeGeometry(depth_mm, normalised_, options_.geometry, cos_incidence, falloff);
  const int bins = Bins();
  const double bins_per_stop = options_.bins_per_stop;
  for (int r = 0; r < size_.height; ++r) {
    const int cell_row = r * options_.grid_rows / size_.height;
    for (int c = 0; c < size_.width; ++c) {
      const float cos_i = cos_incidence(r, c);
      if (!std::isfinite(cos_i) || !std::isfinite(falloff(r, c))) {
        ++report_.pixels_without_geometry;
        continue;
      }
      if (cos_i < options_.geometry.min_cos_incidence) {
        ++report_.pixels_grazing;
        continue;
      }
      const double log2_g = std::log2(cos_i * falloff(r, c));
      const int cell = cell_row * options_.grid_cols + c * options_.grid_cols / size_.width;
      std::uint32_t* h = histograms_.data() + static_cast<size_t>(cell) * 3 * bins;
      for (int k = 0; k < 3; ++k, h += bins) {
        const double v = linear_bgr(r, c)[k];
        int bin = 0;  // NaN and dark values are censored low
        if (v > options_.saturated_linear) {
          bin = bins - 1;
        } else if (v >= options_.dark_linear) {
          const double x = (std::log2(v) - log2_g - options_.log2_min) * bins_per_stop;
          bin = std::clamp(static_cast<int>(std::floor(x)) + 1, 0, bins - 1);
        }
        if (bin == 0 || bin == bins - 1) ++report_.samples_censored;
        ++h[bin];
      }
      ++report_.samples_used;
    }
  }
  ++report_.frames;
}

ReferenceLightResult ReferenceLightEstimator::Estimate() const {
  ReferenceLightResult result;
  result.report = report_;
  const int cols = options_.grid_cols, rows = options_.grid_rows, bins = Bins();
  const size_t cells = static_cast<size_t>(cols) * rows;
  ReferenceLight reference;
  reference.image_size = size_;
  reference.grid_cols = cols;
  reference.grid_rows = rows;
  reference.geometry = options_.geometry;
  reference.log2_bgr.assign(cells, cv::Vec3f());
  for (int k = 0; k < 3; ++k) {
    reference_grid::Grid grid(cells, 0.0);
    std::vector<bool> known(cells, false);
    for (size_t cell = 0; cell < cells; ++cell) {
      const std::uint32_t* h = histograms_.data() + (cell * 3 + k) * bins;
      std::uint64_t total = 0;
      for (int b = 0; b < bins; ++b) total += h[b];
      if (total < static_cast<std::uint64_t>(options_.min_samples_per_cell)) continue;
      const auto value = reference_grid::TrimmedMeanLog2(h, bins, total, options_.trim_fraction);
      if (!value) continue;
      grid[cell] = options_.log2_min + *value / options_.bins_per_stop;
      known[cell] = true;
    }
    const auto estimated = static_cast<int>(std::count(known.begin(), known.end(), true));
    if (estimated == 0) return result;
    result.report.cells_filled += static_cast<int>(cells) - estimated;
    // The smooth model fills and smooths at once, unless it leaves the range the histograms
    // measure by more than a stop (a few cells of censored samples, e.g. a blown-out frame,
    // extrapolated to infinity): then the cells' own values, filled and smoothed.
    const reference_grid::Grid measured = grid;
    const double lo = options_.log2_min - 1.0;
    const double hi = options_.log2_min + static_cast<double>(bins) / options_.bins_per_stop + 1.0;
    const auto in_range = [&] {
      return std::all_of(grid.begin(), grid.end(),
                         [&](double v) { return std::isfinite(v) && v >= lo && v <= hi; });
    };
    if (options_.model_degree > 0 &&
        FitSmoothLight(grid, known, cols, rows, options_.model_degree) >= 0.0 && in_range()) {
      // The smooth model.
    } else {
      grid = measured;
      reference_grid::FillHoles(grid, known, cols, rows);
      if (options_.smoothing_cells > 0)
        reference_grid::SmoothQuadratic(grid, cols, rows, options_.smoothing_cells);
    }
    double sum = 0.0;
    for (size_t cell = 0; cell < cells; ++cell) {
      reference.log2_bgr[cell][k] = static_cast<float>(grid[cell]);
      sum += grid[cell];
    }
    reference.level_bgr[k] = std::exp2(sum / static_cast<double>(cells));
  }
  result.reference = std::move(reference);
  return result;
}

std::size_t ReferenceLightEstimator::memory_bytes() const {
  return histograms_.capacity() * sizeof(std::uint32_t) + normalised_.total() * sizeof(cv::Vec2f);
}

ShadingCorrector::ShadingCorrector(const CameraModel& camera, const ReferenceLight& reference,
                                   const CorrectionOptions& options)
    : options_(options), geometry_(reference.geometry) {
  options_.Check();
  const cv::Size size(camera.intrinsics().width, camera.intrinsics().height);
  CheckSize(size, reference.image_size, "reference light");
  normalised_ = NormalisedCoordinates(camera);
  reference_bgr_ = reference.Render();
}

CorrectedTexture ShadingCorrector::Correct(const cv::Mat3f& linear_bgr,
                                           const cv::Mat1f& depth_mm) const {
  CheckSize(reference_bgr_.size(), linear_bgr.size(), "texture image");
  cv::Mat1f cos_incidence, falloff;
  ComputeGeometry(depth_mm, normalised_, geometry_, cos_incidence, falloff);
  CorrectedTexture out;
  out.linear_bgr.create(linear_bgr.size());
  out.full_mask.create(linear_bgr.size());
  const double w = options_.wall_level_linear;
  // The grey result given the common wall colour (von Kries): 1 for grey.
  const cv::Vec3d tint = options_.target_bgr == cv::Vec3d(0, 0, 0)
                             ? cv::Vec3d(1, 1, 1)
                             : cv::Vec3d(options_.target_bgr[0] / w, options_.target_bgr[1] / w,
                                         options_.target_bgr[2] / w);
  const auto rgb = [](const cv::Vec3d& bgr) { return Eigen::Vector3d(bgr[2], bgr[1], bgr[0]); };
  for (int r = 0; r < linear_bgr.rows; ++r) {
    for (int c = 0; c < linear_bgr.cols; ++c) {
      const bool known = std::isfinite(cos_incidence(r, c)) && std::isfinite(falloff(r, c));
      const double g =
          known ? std::max<double>(cos_incidence(r, c), geometry_.min_cos_incidence) * falloff(r, c)
                : 1.0;
      ++(known ? out.report.pixels_corrected : out.report.pixels_without_depth);
      out.full_mask(r, c) = known ? 255 : 0;
      const cv::Vec3d reference = cv::Vec3d(reference_bgr_(r, c)) * g;
      const cv::Vec3d observed = linear_bgr(r, c);
      if (options_.space == CorrectionSpace::kLinear) {
        out.linear_bgr(r, c) = cv::Vec3f(cv::Vec3d(w * tint[0] * observed[0] / reference[0],
                                                   w * tint[1] * observed[1] / reference[1],
                                                   w * tint[2] * observed[2] / reference[2]));
        continue;
      }
      // Both scaled so that the reference has the luminance of the target grey: the observed
      // L* is then the lightness corrected by the reference's lightness field (and G); the
      // reference scaled to the observed luminance gives the cast at the pixel's lightness.
      const Eigen::Vector3d ref_rgb = rgb(reference), obs_rgb = rgb(observed);
      const double scale = w / LinearRgbToXyz(ref_rgb).y();
      const Eigen::Vector3d obs_lab = LinearRgbToLab(scale * obs_rgb);
      const double luminance_ratio = LinearRgbToXyz(obs_rgb).y() / LinearRgbToXyz(ref_rgb).y();
      const Eigen::Vector3d cast_lab = LinearRgbToLab(scale * luminance_ratio * ref_rgb);
      const Eigen::Vector3d lab(obs_lab.x(), obs_lab.y() - cast_lab.y(),
                                obs_lab.z() - cast_lab.z());
      const Eigen::Vector3d corrected = LabToLinearRgb(lab);
      out.linear_bgr(r, c) = cv::Vec3f(static_cast<float>(corrected.z() * tint[0]),
                                       static_cast<float>(corrected.y() * tint[1]),
                                       static_cast<float>(corrected.x() * tint[2]));
    }
  }
  return out;
}

cv::Mat3b ShadingCorrector::CorrectSrgb8(const cv::Mat3b& srgb_bgr,
                                         const cv::Mat1f& depth_mm) const {
  return Srgb8FromLinear(Correct(LinearFromSrgb8(srgb_bgr), depth_mm).linear_bgr);
}

}  // namespace sewer3d
