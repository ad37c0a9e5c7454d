#pragma once
/// \file
/// Physically based rendering of one structured-light module's two images (docs/simulator.md):
/// the pattern image (projector on, texture light off) and the texture image (texture light
/// on, projector off), with ground-truth depth. Optics: per-pixel supersampling, lens
/// distortion of camera and projector, thin-lens defocus of camera (distributed over the
/// aperture) and projector (circle of confusion blurring each spot), irradiance falloff with
/// distance and incidence, a ring light whose intensity and colour vary with the emission
/// angle, vignetting with per-channel lens shading, white-balance gains; sensor: photon shot
/// noise, read noise, quantisation, optional Bayer mosaic; optionally a real projector's spot
/// placement and power errors and laser speckle (spot_errors.hpp).

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/pattern/binary_array.hpp"
#include "sewer3d/sim/scene.hpp"
#include "sewer3d/sim/sensor.hpp"
#include "sewer3d/sim/spot_errors.hpp"
#include "sewer3d/sim/surface.hpp"
#include "sewer3d/sim/wet_film.hpp"

namespace sewer3d {

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
  /// Texture ring light (white LEDs behind a diffuser round the camera pupil): radiant
  /// intensity ∝ cos^n θ of the emission angle θ from the camera axis (n = this exponent), and
  /// colour bluer on the axis, warmer toward the edge of the beam: RGB gains
  /// (1 + s (t − 0.35), 1, 1 − s (t − 0.35)), t = (1 − cos θ) / (1 − cos 45°), s = this shift.
  double ring_light_exponent = 2.0;
  double ring_light_color_shift = 0.1;
  /// Per-channel lens shading of the texture image on top of cos⁴ (with `vignetting`): channel
  /// c × cos^e_c α, e in R, G, B order; red falls off fastest (the IR-cut filter's edge moves
  /// toward blue at oblique incidence).
  Eigen::Vector3d color_shading{0.6, 0.3, 0.15};
  /// Gains of the texture image's R, G, B channels: a camera's white balance (per shot; the
  /// simulated run sets each module's from the scenario's white_balance_error).
  Eigen::Vector3d white_balance = Eigen::Vector3d::Ones();
  /// Fill RenderedFrame::truth_albedo (texture images only).
  bool truth_albedo = false;
  double speed_mm_s = 0.0;  ///< rig motion during the exposure (0: no motion blur)
  double exposure_ms = 2.0;
  Eigen::Vector3d motion_direction = Eigen::Vector3d::UnitY();  ///< camera frame
  SensorModel sensor;
  /// The projector's and the wall's errors beyond ideal optics (none by default; the `paper`
  /// realism profile sets them, docs/simulator.md "Error sources").
  SpotErrors spot_errors;
  /// The water film where a surface is wet (SurfaceHit::film; dry surfaces ignore it).
  WetFilmOptions wet_film;
  std::uint64_t seed = 1;

  void Check() const;
  /// No noise, no defocus, no ambient light, no vignetting, no motion, a colourless ring
  /// light: for geometric tests.
  static RenderOptions Ideal();
};

struct RenderedFrame {
  cv::Mat1f pattern_signal;  ///< expected pattern signal, fraction of full scale, no noise
  cv::Mat3f texture_signal;  ///< expected texture signal, RGB
  cv::Mat1w pattern;         ///< digital numbers, 0 .. 2^bits − 1
  cv::Mat3w texture;         ///< RGB digital numbers
  /// With sensor.color_filter RGGB: the one-channel raw image (MosaicRggb of `texture`, the
  /// full-colour image shown for tests); else empty.
  cv::Mat1w texture_raw;
  /// With options.truth_albedo: the albedo (linear, R, G, B like texture) averaged over the
  /// pixel's samples that hit the surface — what the texture pixel sees, before light, lens and
  /// sensor; NaN where no sample hits. Else empty.
  cv::Mat3f truth_albedo;
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
