#include "sewer3d/register/photometric.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "sewer3d/core/check.hpp"
#include "sewer3d/register/depth_geometry.hpp"

namespace sewer3d {
namespace {

// ∂π/∂p of a's camera at p (2 × 3, pixels per mm): forward differences, distortion included.
std::optional<Eigen::Matrix<double, 2, 3>> ProjectionJacobian(const CameraModel& camera,
                                                              const Eigen::Vector3d& p,
                                                              const Eigen::Vector2d& px) {
  constexpr double kStepMm = 1e-2;
  Eigen::Matrix<double, 2, 3> j;
  for (int k = 0; k < 3; ++k) {
    const auto moved = camera.Project(p + kStepMm * Eigen::Vector3d::Unit(k));
    if (!moved) return std::nullopt;
    j.col(k) = (*moved - px) / kStepMm;
  }
  return j;
}

// Gaussian blur of σ px; a wide one on an area-averaged copy (steps of σ / 4, blurred there and
// interpolated back): a σ of 60 px on a 5 MP texture would otherwise cost a second a map.
cv::Mat1f Smooth(const cv::Mat1f& image, double sigma_px) {
  cv::Mat1f out;
  const int step = static_cast<int>(std::floor(sigma_px / 4.0));
  if (step < 2) {
    cv::GaussianBlur(image, out, cv::Size(), sigma_px, sigma_px, cv::BORDER_REPLICATE);
    return out;
  }
  cv::Mat1f small;
  cv::resize(image, small, cv::Size((image.cols + step - 1) / step, (image.rows + step - 1) / step),
             0, 0, cv::INTER_AREA);
  // The area average is itself a box of one small pixel (variance 1/12 of a small pixel²).
  const double sigma_small =
      std::sqrt(std::max(sigma_px * sigma_px / (step * step) - 1.0 / 12.0, 0.25));
  cv::GaussianBlur(small, small, cv::Size(), sigma_small, sigma_small, cv::BORDER_REPLICATE);
  cv::resize(small, out, image.size(), 0, 0, cv::INTER_LINEAR);
  return out;
}

struct Grid {
  int half_i = 0, half_j = 0;
  double step = 0.0;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
};

// Correlation at every grid point (row-major, −1 where too few samples).
std::vector<double> Correlations(const Grid& g, const cv::Mat1f& a, const CameraModel& camera_a,
                                 const std::vector<TextureSample>& b, const Rigid3d& start,
                                 const std::vector<Vector6d>& directions, int min_samples) {
  std::vector<double> out;
  for (int i = -g.half_i; i <= g.half_i; ++i) {
    for (int j = -g.half_j; j <= g.half_j; ++j) {
      const Eigen::Vector2d s = g.centre + g.step * Eigen::Vector2d(i, j);
      Vector6d delta = s.x() * directions[0];
      if (directions.size() > 1) delta += s.y() * directions[1];
      const TextureCorrelation c = CorrelateTextures(a, camera_a, b, ApplyUpdate(start, delta));
      out.push_back(c.samples >= min_samples ? c.ncc : -1.0);
    }
  }
  return out;
}

Eigen::Vector2d GridPoint(const Grid& g, size_t index) {
  const int cols = 2 * g.half_j + 1;
  const int i = static_cast<int>(index) / cols - g.half_i;
  const int j = static_cast<int>(index) % cols - g.half_j;
  return g.centre + g.step * Eigen::Vector2d(i, j);
}

// The flat direction of the correlation surface at an inner peak of a 2-D grid (unit, grid
// coordinates) when its curvature there is less than a quarter of the sharp direction's: a
// ridge, as streaks that run along one of the directions searched give. From the 3 × 3
// neighbourhood's second differences; nothing at the border or for a 1-D grid.
std::optional<Eigen::Vector2d> RidgeDirection(const Grid& g, const std::vector<double>& c,
                                              size_t best) {
  const int cols = 2 * g.half_j + 1;
  const int i = static_cast<int>(best) / cols, j = static_cast<int>(best) % cols;
  if (g.half_j == 0 || i == 0 || j == 0 || i == 2 * g.half_i || j == cols - 1) return std::nullopt;
  const auto at = [&](int di, int dj) { return c[(i + di) * cols + (j + dj)]; };
  Eigen::Matrix2d curvature;  // of −c: positive at a peak
  curvature(0, 0) = 2 * at(0, 0) - at(1, 0) - at(-1, 0);
  curvature(1, 1) = 2 * at(0, 0) - at(0, 1) - at(0, -1);
  curvature(0, 1) = curvature(1, 0) = -0.25 * (at(1, 1) - at(1, -1) - at(-1, 1) + at(-1, -1));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(curvature);
  if (!(eig.eigenvalues()(1) > 0.0) || eig.eigenvalues()(0) > 0.25 * eig.eigenvalues()(1))
    return std::nullopt;
  return eig.eigenvectors().col(0);
}

}  // namespace

void PhotometricOptions::Check() const {
  ValidatePositive("blur_px", blur_px);
  ValidatePositive("highpass_mm", highpass_mm);
  ValidateNotNegative("search_range_mm", search_range_mm);
  ValidatePositive("search_step_mm", search_step_mm);
  SEWER3D_VALIDATE(search_sample_step_px >= 1, "search_sample_step_px",
                   "must be >= 1, got " << search_sample_step_px);
  SEWER3D_VALIDATE(max_search_directions >= 0 && max_search_directions <= 2,
                   "max_search_directions", "must be 0, 1 or 2, got " << max_search_directions);
  SEWER3D_VALIDATE(min_ncc > 0.0 && min_ncc < 1.0, "min_ncc", "must lie in (0, 1)");
  ValidateNotNegative("min_ncc_margin", min_ncc_margin);
  SEWER3D_VALIDATE(min_samples >= 10, "min_samples", "must be >= 10, got " << min_samples);
}

GreyTexture MakeGreyTexture(const cv::Mat3b& color_bgr, double highpass_px) {
  GreyTexture t;
  cv::Mat1b grey;
  cv::cvtColor(color_bgr, grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(t.level, CV_32F, 1.0 / 255.0);
  t.mean = Smooth(t.level, highpass_px);
  return t;
}

cv::Mat1f TextureIntensity(const GreyTexture& grey, double blur_px) {
  cv::Mat1f out = Smooth(grey.level, blur_px);
  out -= grey.mean;
  return out;
}

TextureMaps MakeTextureMaps(const GreyTexture& grey, double blur_px) {
  TextureMaps m;
  m.intensity = TextureIntensity(grey, blur_px);
  cv::Sobel(m.intensity, m.du, CV_32F, 1, 0, 1, 0.5, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(m.intensity, m.dv, CV_32F, 0, 1, 1, 0.5, 0.0, cv::BORDER_REPLICATE);
  return m;
}

std::vector<TextureSample> SampleTexture(const std::vector<Eigen::Vector3d>& points_b,
                                         const CameraModel& camera_b,
                                         const cv::Mat1f& intensity_b) {
  std::vector<TextureSample> out;
  out.reserve(points_b.size());
  for (const Eigen::Vector3d& p : points_b) {
    const auto px = camera_b.Project(p);
    if (!px) continue;
    if (const auto i = SampleBilinear(intensity_b, *px)) out.push_back({p, *i});
  }
  return out;
}

PhotometricRows AssociatePhotometric(const TextureMaps& a, const CameraModel& camera_a,
                                     const std::vector<TextureSample>& b, const Rigid3d& pose) {
  struct Hit {
    Eigen::Matrix<double, 1, 6> j;
    double i_a, i_b;
  };
  std::vector<Hit> hits;
  hits.reserve(b.size());
  const Eigen::Matrix3d r = pose.RotationMatrix();
  double sa = 0, sb = 0, sab = 0, sbb = 0;
  for (const TextureSample& s : b) {
    const Eigen::Vector3d x = r * s.point;
    const Eigen::Vector3d p = x + pose.translation;
    const auto px = camera_a.Project(p);
    if (!px) continue;
    const auto i_a = SampleBilinear(a.intensity, *px);
    const auto du = SampleBilinear(a.du, *px), dv = SampleBilinear(a.dv, *px);
    const auto jp = ProjectionJacobian(camera_a, p, *px);
    if (!i_a || !du || !dv || !jp) continue;
    const Eigen::Vector3d m = jp->transpose() * Eigen::Vector2d(*du, *dv);
    Hit h;
    h.j << m.transpose(), x.cross(m).transpose();
    h.i_a = *i_a;
    h.i_b = s.intensity;
    sa += h.i_a;
    sb += h.i_b;
    sab += h.i_a * h.i_b;
    sbb += h.i_b * h.i_b;
    hits.push_back(h);
  }
  PhotometricRows out;
  const double n = static_cast<double>(hits.size());
  const double var_b = sbb - sb * sb / std::max(n, 1.0);
  if (hits.size() >= 2 && var_b > 1e-12) {
    out.gain = (sab - sa * sb / n) / var_b;
    out.offset = (sa - out.gain * sb) / n;
  }
  out.rows.reserve(hits.size());
  for (const Hit& h : hits) out.rows.push_back({h.j, h.i_a - (out.gain * h.i_b + out.offset)});
  return out;
}

TextureCorrelation CorrelateTextures(const cv::Mat1f& intensity_a, const CameraModel& camera_a,
                                     const std::vector<TextureSample>& b, const Rigid3d& pose) {
  const Eigen::Matrix3d r = pose.RotationMatrix();
  double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (const TextureSample& s : b) {
    const auto px = camera_a.Project(r * s.point + pose.translation);
    if (!px) continue;
    const auto i_a = SampleBilinear(intensity_a, *px);
    if (!i_a) continue;
    n += 1;
    sa += *i_a;
    sb += s.intensity;
    saa += *i_a * *i_a;
    sbb += s.intensity * s.intensity;
    sab += *i_a * s.intensity;
  }
  TextureCorrelation out;
  out.samples = static_cast<int>(n);
  if (n < 2) return out;
  const double var = (saa - sa * sa / n) * (sbb - sb * sb / n);
  if (var > 0.0) out.ncc = (sab - sa * sb / n) / std::sqrt(var);
  return out;
}

TextureSearchResult SearchTexture(const TextureSearchInput& in, const CameraModel& camera_a,
                                  const Rigid3d& start, const std::vector<Vector6d>& directions,
                                  const PhotometricOptions& options) {
  TextureSearchResult out;
  out.pose = start;
  out.ncc_start = CorrelateTextures(in.fine_a, camera_a, in.fine_b, start).ncc;
  out.overlap = CorrelateTextures(in.coarse_a, camera_a, in.coarse_b, start).samples;
  if (directions.empty() || out.overlap < options.min_samples) return out;
  const int half = static_cast<int>(std::floor(options.search_range_mm / options.search_step_mm));
  Grid coarse{half, directions.size() > 1 ? half : 0, options.search_step_mm, {0, 0}};
  const std::vector<double> c = Correlations(coarse, in.coarse_a, camera_a, in.coarse_b, start,
                                             directions, options.min_samples);
  const size_t best = std::max_element(c.begin(), c.end()) - c.begin();
  const Eigen::Vector2d at = GridPoint(coarse, best);
  // On a ridge only the sharp direction is found; along the ridge the start stays.
  const std::optional<Eigen::Vector2d> flat = RidgeDirection(coarse, c, best);
  out.ridge = flat.has_value();
  out.ncc_other = -1.0;
  for (size_t k = 0; k < c.size(); ++k) {
    const Eigen::Vector2d d = GridPoint(coarse, k) - at;
    const double apart =
        flat ? std::abs(d.x() * flat->y() - d.y() * flat->x()) : d.cwiseAbs().maxCoeff();
    if (apart > 1.5 * coarse.step) out.ncc_other = std::max(out.ncc_other, c[k]);
  }
  out.ncc_peak = c[best];
  out.clear = c[best] >= options.min_ncc && c[best] - out.ncc_other >= options.min_ncc_margin;
  if (!out.clear) return out;
  std::vector<Vector6d> refine = directions;
  Grid fine{4, coarse.half_j > 0 ? 4 : 0, 0.25 * coarse.step, at};
  if (flat) {
    out.along_ridge = flat->x() * directions[0] + flat->y() * directions[1];
    const Eigen::Vector2d sharp(-flat->y(), flat->x());
    refine = {sharp.x() * directions[0] + sharp.y() * directions[1]};
    fine = Grid{4, 0, 0.25 * coarse.step, {at.dot(sharp), 0.0}};
  }
  const std::vector<double> f =
      Correlations(fine, in.fine_a, camera_a, in.fine_b, start, refine, options.min_samples);
  const size_t peak = std::max_element(f.begin(), f.end()) - f.begin();
  out.ncc_peak = f[peak];
  const Eigen::Vector2d shift = GridPoint(fine, peak);
  Vector6d delta = shift.x() * refine[0];
  if (refine.size() > 1) delta += shift.y() * refine[1];
  out.shift_mm = shift;
  out.pose = ApplyUpdate(start, delta);
  return out;
}

}  // namespace sewer3d
