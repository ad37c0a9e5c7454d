#include "sewer3d/decode/spots.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

void SpotOptions::Check() const {
  SEWER3D_CHECK(min_area_px >= 1 && max_area_px >= min_area_px, "spot area range");
  SEWER3D_CHECK(max_aspect >= 1.0, "max_aspect");
}

namespace {

// Weighted centroid over the box, skipping other components' pixels.
template <typename Pixel>
bool Centroid(const cv::Mat& image, const cv::Mat1i& labels, const cv::Mat1f& local_mean, int label, int u0,
              int v0, int u1, int v1, Spot& spot) {
  double sum = 0.0, su = 0.0, sv = 0.0, peak = 0.0;
  for (int v = v0; v <= v1; ++v) {
    const Pixel* row = image.ptr<Pixel>(v);
    const int* label_row = labels[v];
    const float* mean_row = local_mean[v];
    for (int u = u0; u <= u1; ++u) {
      const int other = label_row[u];
      if (other != 0 && other != label) continue;  // a neighbouring spot's pixels
      const double weight = std::max(0.0, static_cast<double>(row[u]) - mean_row[u]);
      sum += weight;
      su += weight * u;
      sv += weight * v;
      peak = std::max(peak, weight);
    }
  }
  if (sum <= 0.0) return false;
  spot.centre_px = {su / sum, sv / sum};
  spot.contrast = peak;
  return true;
}

}  // namespace

std::vector<Spot> DetectSpots(const cv::Mat& image, const cv::Mat1b& mask,
                              const cv::Mat1f& local_mean, const SpotOptions& options,
                              SpotWorkspace* workspace) {
  options.Check();
  SEWER3D_CHECK(image.size() == mask.size() && image.size() == local_mean.size(), "sizes differ");
  SEWER3D_CHECK(image.channels() == 1 && (image.depth() == CV_8U || image.depth() == CV_16U),
                "spots need an 8-bit or 16-bit grey image");
  SpotWorkspace local;
  SpotWorkspace& ws = workspace ? *workspace : local;
  const int count = cv::connectedComponentsWithStats(mask, ws.labels, ws.stats, ws.centroids, 8, CV_32S);
  const cv::Mat& stats = ws.stats;
  std::vector<Spot> spots;
  spots.reserve(count);
  for (int label = 1; label < count; ++label) {
    const int* st = stats.ptr<int>(label);
    const int area = st[cv::CC_STAT_AREA], w = st[cv::CC_STAT_WIDTH], h = st[cv::CC_STAT_HEIGHT];
    if (area < options.min_area_px || area > options.max_area_px) continue;
    if (std::max(w, h) > options.max_aspect * std::min(w, h)) continue;
    const int u0 = std::max(0, st[cv::CC_STAT_LEFT] - 1);
    const int v0 = std::max(0, st[cv::CC_STAT_TOP] - 1);
    const int u1 = std::min(image.cols - 1, u0 + w + 1), v1 = std::min(image.rows - 1, v0 + h + 1);
    Spot spot;
    spot.area_px = area;
    const bool ok = image.depth() == CV_8U
                        ? Centroid<std::uint8_t>(image, ws.labels, local_mean, label, u0, v0, u1, v1, spot)
                        : Centroid<std::uint16_t>(image, ws.labels, local_mean, label, u0, v0, u1, v1, spot);
    if (ok) spots.push_back(spot);
  }
  return spots;
}

}  // namespace sewer3d
