#pragma once
/// \file
/// The camera sensor of the simulator (docs/simulator.md): photon shot noise, read noise,
/// quantisation, and the optional Bayer colour filter array.

#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <string_view>

namespace sewer3d {

/// The colour filter array over the texture camera's pixels.
enum class ColorFilter {
  kNone,  ///< a full RGB value per pixel (as if demosaiced in the camera)
  /// Bayer RGGB: row 0 is R G R G …, row 1 is G B G B …; the image is one channel. OpenCV
  /// demosaics it with cv::COLOR_BayerBG2BGR, not BayerRG2BGR: OpenCV names a layout by the
  /// 2 × 2 block that starts at row 1, column 1 (verified in sensor_test.cpp).
  kRggb,
};

/// "none", "RGGB" (scenario files, render JSON and run.json's "color_filter").
const char* ColorFilterName(ColorFilter filter);
/// The filter named `name`; nullopt when it names none.
std::optional<ColorFilter> ParseColorFilter(std::string_view name);

struct SensorModel {
  double full_well_e = 6000.0;                    ///< electrons at full scale
  double read_noise_e = 3.0;                      ///< read noise, electrons RMS
  int bits = 8;                                   ///< ADC resolution, 8..12
  bool noise = true;                              ///< photon shot noise and read noise
  ColorFilter color_filter = ColorFilter::kNone;  ///< of the texture image
};

/// Digital number of a pixel's `signal` (fraction of full scale): electrons, shot and read
/// noise from hashes of (seed, pixel, channel) (deterministic), rounding, clipping to
/// 0 .. 2^bits − 1.
std::uint16_t Digitise(double signal, const SensorModel& sensor, std::uint64_t seed,
                       std::uint64_t pixel, std::uint64_t channel);

/// The one-channel raw image a Bayer RGGB sensor records: each pixel keeps the channel of its
/// filter from `rgb` (channels in R, G, B order as RenderedFrame::texture). Sampling after the
/// noise is exact here: each channel's noise is independent per pixel.
cv::Mat1w MosaicRggb(const cv::Mat3w& rgb);

}  // namespace sewer3d
