#include "sewer3d/simeval/picture.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "sewer3d/io/model_io.hpp"

namespace sewer3d {

void DrawLabel(cv::Mat3b& image, const std::string& text, cv::Point at, double scale) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
}

void DrawColourBar(cv::Mat3b& image, cv::Point top_left, int height, double range_mm) {
  cv::Mat1f ramp(height, 1);
  for (int y = 0; y < height; ++y)
    ramp(y, 0) = static_cast<float>(range_mm * (1.0 - 2.0 * y / std::max(1, height - 1)));
  cv::Mat3b bar;
  cv::resize(DisplacementView(ramp, range_mm), bar, {20, height}, 0, 0, cv::INTER_NEAREST);
  bar.copyTo(image(cv::Rect(top_left.x, top_left.y, 20, height)));
  const int x = top_left.x + 24, y = top_left.y;
  DrawLabel(image, fmt::format("+{:g} mm", range_mm), {x, y + 10});
  DrawLabel(image, "0", {x, y + height / 2 + 5});
  DrawLabel(image, fmt::format("-{:g} mm", range_mm), {x, y + height});
}

}  // namespace sewer3d
