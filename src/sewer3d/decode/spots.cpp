#include "sewer3d/decode/spots.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

void SpotOptions::Check() const {
  SEWER3D_CHECK(min_area_px >= 1 && max_area_px >= min_area_px, "spot area range");
  SEWER3D_CHECK(max_aspect >= 1.0, "max_aspect");
}

std::vector<Spot> DetectSpots(const cv::Mat& image, const cv::Mat1b& mask,
                              const cv::Mat1f& local_mean, const SpotOptions& options) {
  options.Check();
  SEWER3D_CHECK(image.size() == mask.size() && image.size() == local_mean.size(), "sizes differ");
  SEWER3D_CHECK(image.channels() == 1 && (image.depth() == CV_8U || image.depth() == CV_16U),
                "spots need an 8-bit or 16-bit grey image");
  cv::Mat1i labels;
  cv::Mat stats, centroids;
  const int count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  std::vector<Spot> spots;
  spots.reserve(count);
  for (int label = 1; label < count; ++label) {
    const int area = stats.at<int>(label, cv::CC_STAT_AREA);
    const int w = stats.at<int>(label, cv::CC_STAT_WIDTH), h = stats.at<int>(label, cv::CC_STAT_HEIGHT);
    if (area < options.min_area_px || area > options.max_area_px) continue;
    if (std::max(w, h) > options.max_aspect * std::min(w, h)) continue;
    const int u0 = std::max(0, stats.at<int>(label, cv::CC_STAT_LEFT) - 1);
    const int v0 = std::max(0, stats.at<int>(label, cv::CC_STAT_TOP) - 1);
    const int u1 = std::min(image.cols - 1, u0 + w + 1), v1 = std::min(image.rows - 1, v0 + h + 1);
    double sum = 0.0, su = 0.0, sv = 0.0, peak = 0.0;
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) {
        const int other = labels(v, u);
        if (other != 0 && other != label) continue;  // a neighbouring spot's pixels
        const double x = image.depth() == CV_8U ? image.at<std::uint8_t>(v, u) : image.at<std::uint16_t>(v, u);
        const double weight = std::max(0.0, x - local_mean(v, u));
        sum += weight;
        su += weight * u;
        sv += weight * v;
        peak = std::max(peak, weight);
      }
    }
    if (sum <= 0.0) continue;
    spots.push_back({Eigen::Vector2d(su / sum, sv / sum), area, peak});
  }
  return spots;
}

}  // namespace sewer3d
