#include "sewer3d/report/map_images.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/core.hpp>

namespace sewer3d {
namespace {

struct Stop {
  double t;
  double r, g, b;
};
// A blue–white–red scale, lighter toward 0 so small relief stays readable.
constexpr std::array<Stop, 5> kStops{{{-1.0, 40, 70, 170},
                                      {-0.5, 115, 165, 225},
                                      {0.0, 246, 246, 246},
                                      {0.5, 235, 140, 100},
                                      {1.0, 170, 30, 40}}};

}  // namespace

cv::Vec3b HeatColour(double t) {
  t = std::clamp(t, -1.0, 1.0);
  std::size_t k = 1;
  while (k + 1 < kStops.size() && t > kStops[k].t) ++k;
  const Stop& a = kStops[k - 1];
  const Stop& b = kStops[k];
  const double w = (t - a.t) / (b.t - a.t);
  auto mix = [w](double x, double y) { return cv::saturate_cast<std::uint8_t>(x + w * (y - x)); };
  return {mix(a.b, b.b), mix(a.g, b.g), mix(a.r, b.r)};
}

cv::Mat3b HeatImage(const cv::Mat1f& displacement_mm, double range_mm) {
  cv::Mat3b out(displacement_mm.size(), cv::Vec3b(40, 40, 40));
  for (int r = 0; r < out.rows; ++r) {
    for (int c = 0; c < out.cols; ++c) {
      const float d = displacement_mm(r, c);
      if (std::isfinite(d)) out(r, c) = HeatColour(d / range_mm);
    }
  }
  return out;
}

std::string HeatGradientCss() {
  std::string css = "linear-gradient(to right";
  for (const Stop& s : kStops)
    css += fmt::format(", rgb({:.0f},{:.0f},{:.0f}) {:.0f}%", s.r, s.g, s.b, 50.0 * (s.t + 1.0));
  return css + ")";
}

cv::Mat3b StationAlongX(const cv::Mat3b& image) {
  cv::Mat3b out;
  if (!image.empty()) cv::transpose(image, out);
  return out;
}

}  // namespace sewer3d
