#include "sewer3d/simeval/residual_image.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/model_io.hpp"
#include "sewer3d/simeval/picture.hpp"

namespace sewer3d {
namespace {

double Rms(const std::vector<double>& values, int* count) {
  double sum2 = 0.0;
  *count = 0;
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    sum2 += v * v;
    ++*count;
  }
  return *count > 0 ? std::sqrt(sum2 / *count) : 0.0;
}

// Each value replaced by the mean of the values whose view positions share its cell of a grid
// `cells` across (square cells over the extent from `lo`).
void SmoothInCells(const std::vector<Eigen::Vector2d>& view, const Eigen::Vector2d& lo,
                   const Eigen::Vector2d& extent, int cells, std::vector<float>& value) {
  const double side = extent.x() / cells;
  const int rows = std::max(1, static_cast<int>(std::ceil(extent.y() / side)));
  std::vector<double> sum(static_cast<size_t>(cells + 1) * (rows + 1), 0.0);
  std::vector<int> count(sum.size(), 0), cell_of(view.size());
  for (size_t i = 0; i < view.size(); ++i) {
    const Eigen::Vector2d q = (view[i] - lo) / side;
    const int c = std::clamp(static_cast<int>(q.x()), 0, cells);
    const int r = std::clamp(static_cast<int>(q.y()), 0, rows);
    cell_of[i] = r * (cells + 1) + c;
    sum[cell_of[i]] += value[i];
    ++count[cell_of[i]];
  }
  for (size_t i = 0; i < view.size(); ++i)
    value[i] = static_cast<float>(sum[cell_of[i]] / count[cell_of[i]]);
}

}  // namespace

double ResidualRange(const std::vector<double>& residual_mm) {
  int n = 0;
  const double wanted = 3.0 * Rms(residual_mm, &n);
  for (double decade = 0.1; decade < 1e6; decade *= 10.0)
    for (const double step : {0.5, 1.0, 2.0})
      if (step * decade >= wanted) return step * decade;
  return 1e6;
}

std::vector<double> RayResiduals(const Scene& scene, const std::vector<Eigen::Vector3d>& points) {
  std::vector<double> out;
  out.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    const double range = p.norm();
    const auto hit = range > 0.0 ? Intersect(scene, Eigen::Vector3d::Zero(), p / range)
                                 : std::optional<SurfaceHit>();
    out.push_back(hit ? range - hit->point.norm() : std::numeric_limits<double>::quiet_NaN());
  }
  return out;
}

cv::Mat3b ResidualImage(const std::vector<Eigen::Vector3d>& points,
                        const std::vector<double>& residual_mm,
                        const ResidualImageOptions& options) {
  SEWER3D_VALIDATE(points.size() == residual_mm.size(), "residual_mm",
                   "has " << residual_mm.size() << " values for " << points.size() << " points");
  ValidatePositive("width_px", options.width_px);
  ValidateNotNegative("range_mm", options.range_mm);
  ValidateNotNegative("smoothing_cells", options.smoothing_cells);
  // Viewing directions of the drawn points and their extent.
  std::vector<Eigen::Vector2d> view;
  std::vector<float> value;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!(points[i].z() > 0.0) || !std::isfinite(residual_mm[i])) continue;
    view.push_back(points[i].head<2>() / points[i].z());
    value.push_back(static_cast<float>(residual_mm[i]));
    lo = lo.cwiseMin(view.back());
    hi = hi.cwiseMax(view.back());
  }
  const int width = options.width_px;
  const Eigen::Vector2d extent = (hi - lo).cwiseMax(1e-9);
  if (options.smoothing_cells > 0) SmoothInCells(view, lo, extent, options.smoothing_cells, value);
  const double range = options.range_mm > 0.0
                           ? options.range_mm
                           : ResidualRange(std::vector<double>(value.begin(), value.end()));
  const int height =
      view.empty() ? width * 3 / 4
                   : std::clamp(static_cast<int>(std::lround(width * extent.y() / extent.x())), 1,
                                4 * width);
  // Discs about the points' spacing across, so a dense cloud reads as a surface.
  const double spacing =
      view.empty() ? 1.0 : std::sqrt(static_cast<double>(width) * height / view.size());
  const int radius = std::max(1, static_cast<int>(std::lround(0.8 * spacing)));
  const cv::Mat1f values(static_cast<int>(value.size()), 1, value.data());
  const cv::Mat3b colours = DisplacementView(values, range);
  const int left = 20, top = 40, right = 130, bottom = 20;
  cv::Mat3b out(height + top + bottom, width + left + right, cv::Vec3b(255, 255, 255));
  cv::Mat3b canvas = out(cv::Rect(left, top, width, height));
  canvas.setTo(cv::Vec3b(0, 0, 0));
  const double scale = (width - 1) / extent.x();
  for (size_t i = 0; i < view.size(); ++i) {
    const Eigen::Vector2d at = (view[i] - lo) * scale;
    const cv::Vec3b& c = colours(static_cast<int>(i), 0);
    cv::circle(canvas,
               {static_cast<int>(std::lround(at.x())), static_cast<int>(std::lround(at.y()))},
               radius, cv::Scalar(c[0], c[1], c[2]), cv::FILLED);
  }
  int n = 0;
  const double rms = Rms(residual_mm, &n);
  DrawLabel(out, options.title, {left, 16});
  DrawLabel(out,
            fmt::format("{} points, RMS {:.4f} mm, colours to +-{:g} mm{}", n, rms, range,
                        options.smoothing_cells > 0
                            ? fmt::format(", mean over {} cells across", options.smoothing_cells)
                            : ""),
            {left, 33});
  DrawColourBar(out, {left + width + 15, top}, std::min(height, 300), range);
  return out;
}

std::vector<NamedPicture> ResidualPictures(const std::vector<Eigen::Vector3d>& points,
                                           const std::vector<double>& fitted_mm,
                                           const std::string& fitted_title, const Scene* truth) {
  ResidualImageOptions single;
  single.title = fitted_title;
  ResidualImageOptions smoothed = single;
  smoothed.smoothing_cells =
      std::max(4, static_cast<int>(std::sqrt(static_cast<double>(points.size()) / 50.0 * 4 / 3)));
  std::vector<NamedPicture> out{
      {"residuals.png", ResidualImage(points, fitted_mm, single)},
      {"residuals_smoothed.png", ResidualImage(points, fitted_mm, smoothed)}};
  if (truth == nullptr) return out;
  single.title = smoothed.title = "signed distance from the true surface along each point's ray";
  const std::vector<double> to_truth = RayResiduals(*truth, points);
  out.push_back({"truth_residuals.png", ResidualImage(points, to_truth, single)});
  out.push_back({"truth_residuals_smoothed.png", ResidualImage(points, to_truth, smoothed)});
  return out;
}

}  // namespace sewer3d
