#pragma once
/// \file
/// Error sources of a real spot projector that the ideal renderer lacks (issue 17; physical
/// basis and defaults in docs/simulator.md, "Error sources"):
/// - element placement: each element's spot sits off its design centre by a fixed Gaussian
///   offset (mask or diffractive-element manufacture; the same in every frame of a module,
///   so calibration, which uses the design centres, cannot see it);
/// - element gain: each spot's power differs by a fixed Gaussian factor;
/// - speckle: a coherent source's light scattered by a rough wall interferes into a granular
///   pattern in the camera image (subjective speckle), grain size 2.44 λ N on the sensor
///   (λ the wavelength, N the camera's f-number); fully developed speckle has intensity
///   contrast 1, reduced by partial coherence and pixel integration.
/// - subsurface scattering: light entering the wall leaves it again around the entry point, so a
///   spot on the wall is its projected disk blurred by a Gaussian of the material's scattering
///   length (cement paste and glaze little, translucent plastic more);
/// - calibration error: the module that lights and sees the scene differs from the module file
///   (the calibrated one the decoder uses) by draws within a calibration's uncertainties.
/// Pure functions of their inputs; no I/O.

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/camera/module.hpp"
#include "sewer3d/sim/material.hpp"

namespace sewer3d {

struct SpotErrors {
  double placement_sigma_px = 0.0;  ///< per-element centre offset, projector px, per axis
  double gain_sigma = 0.0;          ///< per-element relative power, standard deviation
  double speckle_contrast = 0.0;    ///< 0: none; 1: fully developed
  double wavelength_nm = 850.0;     ///< near-infrared laser
  /// Lens distortion the module's 3-term radial model cannot represent (a decentred element, a
  /// tilted sensor): tangential (p1, p2) and thin-prism (s1, s2) terms of this magnitude, in
  /// directions fixed by the seed, on the camera and on the projector. 1e-3 moves a corner of
  /// the default camera's image by about a pixel.
  double lens_residual = 0.0;
  /// Micro-relief of the wall below the spot scale (cement skin, sand grains, pores), RMS
  /// height and correlation length: a plane of real concrete is not a plane to 0.05 mm. Of
  /// mineral walls (concrete, vitrified clay, sediment) and of plastic (PVC, PE: smooth to
  /// micrometres).
  double relief_mm = 0.0;
  double relief_plastic_mm = 0.0;
  double relief_scale_mm = 0.5;
  /// Subsurface scattering length (Gaussian sigma on the wall, mm) of mineral walls (concrete,
  /// vitrified clay, sediment) and of plastic.
  double subsurface_mm = 0.0;
  double subsurface_plastic_mm = 0.0;
  /// Calibration error, one standard deviation of each draw (ActualModule): focal lengths and
  /// principal points of camera and projector (their own px), projector centre per axis (mm),
  /// projector rotation per axis (deg).
  double calibration_focal_px = 0.0;
  double calibration_centre_px = 0.0;
  double calibration_baseline_mm = 0.0;
  double calibration_rotation_deg = 0.0;
  std::uint64_t projector_seed = 1;  ///< the projector's own (fixed per module)
  /// 0: the px members are the rendered module's own pixels. > 0: they are pixels of a camera
  /// this wide (a profile's, for the full-size module) and scale with the rendered module's
  /// camera width, so that a reduced-size module errs by the same angles (AtCameraWidth).
  int reference_width_px = 0;
  void Check() const;
  bool Any() const {
    return placement_sigma_px > 0.0 || gain_sigma > 0.0 || speckle_contrast > 0.0 ||
           lens_residual > 0.0 || relief_mm > 0.0 || relief_plastic_mm > 0.0 ||
           subsurface_mm > 0.0 || subsurface_plastic_mm > 0.0 || CalibrationError();
  }
  bool CalibrationError() const {
    return calibration_focal_px > 0.0 || calibration_centre_px > 0.0 ||
           calibration_baseline_mm > 0.0 || calibration_rotation_deg > 0.0;
  }
};

/// The named realism profiles: "ideal" (no error source) and "paper" (a laser projector and
/// wall whose errors match the accuracy the paper reports, docs/accuracy.md). nullopt for
/// other names.
std::optional<SpotErrors> RealismProfile(const std::string& name);

/// `errors` for a module whose camera is `camera_width` px wide: the px members (placement,
/// calibration focal length and principal point) scaled by camera_width / reference_width_px,
/// reference_width_px then 0. Unchanged when reference_width_px is 0.
SpotErrors AtCameraWidth(const SpotErrors& errors, int camera_width);

/// The module's own errors of `errors` (placement, gain, speckle, lens residual): without the
/// wall's (relief, subsurface scattering) and without calibration error. What checkerboard
/// captures for a calibration see.
SpotErrors ModuleOwnErrors(const SpotErrors& errors);

/// Fixed offset (projector px) of element (r, c), absolute projector indices.
Eigen::Vector2d ElementOffset(const SpotErrors& errors, int r, int c);

/// Fixed power factor (> 0, mean 1) of element (r, c).
double ElementGain(const SpotErrors& errors, int r, int c);

/// One lens's residual distortion: Brown–Conrady decentring (p1, p2) and thin-prism (s1, s2)
/// coefficients, fixed per lens (computed once, applied per ray).
struct LensResidual {
  double p1 = 0.0, p2 = 0.0, s1 = 0.0, s2 = 0.0;
  /// Where the residual moves a pixel of a lens with these intrinsics (px, added to the pixel
  /// the module's model gives).
  [[nodiscard]] Eigen::Vector2d ShiftPx(const CameraIntrinsics& intrinsics,
                                        const Eigen::Vector2d& pixel) const;
};

/// The residual of a lens of the module: `lens` 0 for the camera, 1 for the projector; all
/// zero without errors.lens_residual.
LensResidual MakeLensResidual(const SpotErrors& errors, int lens);

/// Height (mm, toward the viewer) of the wall's micro-relief at a surface point (mm in the
/// surface's own coordinates): Gaussian lattice values at the correlation length, bilinear
/// between them, scaled to the material's RMS (ReliefMm). Deterministic for the surface's seed.
double WallRelief(const SpotErrors& errors, Material material, std::uint64_t seed,
                  const Eigen::Vector2d& surface_mm);

/// Micro-relief RMS (mm) of a material.
double ReliefMm(const SpotErrors& errors, Material material);

/// Subsurface scattering sigma (mm on the wall) of a material.
double SubsurfaceMm(const SpotErrors& errors, Material material);

/// The module that renders the scene when `calibrated` is what the module file says: its
/// camera's and projector's focal lengths, principal points, projector centre and rotation
/// moved by Gaussian draws of the calibration sigmas, fixed by projector_seed. `calibrated`
/// itself without calibration error.
ModuleDescription ActualModule(const ModuleDescription& calibrated, const SpotErrors& errors);

/// Speckle grain (intensity correlation length, camera px) for a camera of the given f-number
/// and pixel pitch.
double SpeckleGrainPx(const SpotErrors& errors, double f_number, double pixel_pitch_mm);

/// Multiplies `signal` by a speckle field of mean 1, the errors' contrast and `grain_px`,
/// deterministic for `seed` (a frame's own: the wall and the carrier move between frames).
void ApplySpeckle(cv::Mat1f& signal, const SpotErrors& errors, double grain_px, std::uint64_t seed);

}  // namespace sewer3d
