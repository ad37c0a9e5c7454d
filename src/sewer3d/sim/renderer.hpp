#pragma once
/// \file
/// Physically based rendering of one structured-light module's two images (docs/simulator.md):
/// the pattern image (projector on, texture light off) and the texture image (texture light
/// on, projector off), with ground-truth depth. Optics: per-pixel supersampling, lens
/// distortion of camera and projector, thin-lens defocus of camera (distributed over the
/// aperture) and projector (circle of confusion blurring each spot), irradiance falloff with
/// distance and incidence, vignetting; sensor: photon shot noise, read noise, quantisation.

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/pattern/binary_array.hpp"
#include "sewer3d/sim/scene.hpp"
#include "sewer3d/sim/surface.hpp"

namespace sewer3d {

struct SensorModel {
  double full_well_e = 6000.0;  ///< electrons at full scale
  double read_noise_e = 3.0;    ///< read noise, electrons RMS
  int bits = 8;                 ///< ADC resolution, 8..12
  bool noise = true;            ///< photon shot noise and read noise
};

/// Which images a call renders (a capture run renders each image of a triplet at its own
/// instant, so it asks for one at a time).
enum class RenderImages { kBoth, kPattern, kTexture };

struct RenderOptions {
  RenderImages images = RenderImages::kBoth;
  bool truth_depth = true;  ///< trace the pixel-centre ray for truth_depth (else all NaN)
  int supersampling = 3;    ///< S: S x S samples per pixel (area and aperture)
  /// Physical width of the camera sensor (2592 x 2.2 µm); with the image width it gives the
  /// pixel pitch, hence the physical focal length and aperture of camera and projector.
  double sensor_width_mm = 5.7;
  double camera_f_number = 8.0;     ///< 0: pinhole camera (no defocus)
  double camera_focus_mm = 112.5;   ///< harmonic mean of 75 and 225 mm: equal blur at both ends
  double projector_f_number = 8.0;  ///< 0: no projector defocus
  double projector_focus_mm = 112.5;
  double projector_psf_px = 0.3;  ///< Gaussian sigma of the projector optics at focus, proj. px
  /// Signal (fraction of full scale) from albedo 0.5 facing the camera at 150 mm on the axis.
  double texture_level = 0.6;
  double pattern_level = 0.8;
  double ambient_level = 0.02;  ///< ambient light, same reference, in both images
  bool vignetting = true;       ///< cos⁴ falloff of camera and projector lenses
  double speed_mm_s = 0.0;      ///< rig motion during the exposure (0: no motion blur)
  double exposure_ms = 2.0;
  Eigen::Vector3d motion_direction = Eigen::Vector3d::UnitY();  ///< camera frame
  SensorModel sensor;
  std::uint64_t seed = 1;

  void Check() const;
  /// No noise, no defocus, no ambient light, no vignetting, no motion: for geometric tests.
  static RenderOptions Ideal();
};

struct RenderedFrame {
  cv::Mat1f pattern_signal;  ///< expected pattern signal, fraction of full scale, no noise
  cv::Mat3f texture_signal;  ///< expected texture signal, RGB
  cv::Mat1w pattern;         ///< digital numbers, 0 .. 2^bits − 1
  cv::Mat3w texture;         ///< RGB digital numbers
  cv::Mat1f truth_depth;     ///< z (mm) of the surface at each pixel centre; NaN: no surface
  std::int64_t samples = 0;  ///< rays traced
};

/// Renders the frame; multi-threaded, deterministic for options.seed. Images not asked for
/// in options.images are left black.
RenderedFrame RenderFrame(const ModuleDescription& module, const BinaryArray& pattern,
                          const Surface& surface, const RenderOptions& options);
RenderedFrame RenderFrame(const ModuleDescription& module, const BinaryArray& pattern,
                          const Scene& scene, const RenderOptions& options);

}  // namespace sewer3d
