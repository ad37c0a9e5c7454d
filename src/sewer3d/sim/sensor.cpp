#include "sewer3d/sim/sensor.hpp"

#include <algorithm>
#include <cmath>

#include "sewer3d/sim/material.hpp"

namespace sewer3d {

const char* ColorFilterName(ColorFilter filter) {
  return filter == ColorFilter::kRggb ? "RGGB" : "none";
}

std::optional<ColorFilter> ParseColorFilter(std::string_view name) {
  if (name == "none") return ColorFilter::kNone;
  if (name == "RGGB") return ColorFilter::kRggb;
  return std::nullopt;
}

std::uint16_t Digitise(double signal, const SensorModel& sensor, std::uint64_t seed,
                       std::uint64_t pixel, std::uint64_t channel) {
  double electrons = std::max(0.0, signal) * sensor.full_well_e;
  if (sensor.noise) {
    electrons += std::sqrt(electrons) * HashNormal(seed, pixel, channel);
    electrons += sensor.read_noise_e * HashNormal(seed, pixel, channel + 100);
  }
  const double max_dn = (1 << sensor.bits) - 1;
  return static_cast<std::uint16_t>(
      std::clamp(std::round(electrons / sensor.full_well_e * max_dn), 0.0, max_dn));
}

cv::Mat1w MosaicRggb(const cv::Mat3w& rgb) {
  cv::Mat1w raw(rgb.size());
  for (int v = 0; v < rgb.rows; ++v) {
    for (int u = 0; u < rgb.cols; ++u) {
      // R at (even, even), B at (odd, odd), G elsewhere; rgb holds R, G, B.
      const int channel = (v % 2) + (u % 2);
      raw(v, u) = rgb(v, u)[channel];
    }
  }
  return raw;
}

}  // namespace sewer3d
