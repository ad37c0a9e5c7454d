#include "sewer3d/sim/spot_errors.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/material.hpp"

namespace sewer3d {

namespace {

// An integer lattice point (element row and column, relief cell) as one hash input.
std::uint64_t LatticeKey(int r, int c) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(r)) << 32) |
         static_cast<std::uint32_t>(c);
}

}  // namespace

void SpotErrors::Check() const {
  // Beyond a pitch's worth the spots would cross their neighbours; beyond these the pattern is
  // no longer a pattern.
  SEWER3D_VALIDATE(placement_sigma_px >= 0.0 && placement_sigma_px <= 2.0,
                   "spot_placement_sigma_px",
                   "must be 0..2 projector px, got " << placement_sigma_px);
  SEWER3D_VALIDATE(gain_sigma >= 0.0 && gain_sigma <= 0.5, "spot_gain_sigma",
                   "must be 0..0.5, got " << gain_sigma);
  SEWER3D_VALIDATE(speckle_contrast >= 0.0 && speckle_contrast <= 1.0, "speckle_contrast",
                   "must be 0..1, got " << speckle_contrast);
  SEWER3D_VALIDATE(lens_residual >= 0.0 && lens_residual <= 0.05, "lens_residual",
                   "must be 0..0.05, got " << lens_residual);
  SEWER3D_VALIDATE(relief_mm >= 0.0 && relief_mm <= 1.0, "relief_mm",
                   "must be 0..1 mm, got " << relief_mm);
  SEWER3D_VALIDATE(relief_plastic_mm >= 0.0 && relief_plastic_mm <= 1.0, "relief_plastic_mm",
                   "must be 0..1 mm, got " << relief_plastic_mm);
  SEWER3D_VALIDATE(relief_scale_mm >= 0.05 && relief_scale_mm <= 50.0, "relief_scale_mm",
                   "must be 0.05..50 mm, got " << relief_scale_mm);
  SEWER3D_VALIDATE(subsurface_mm >= 0.0 && subsurface_mm <= 2.0, "subsurface_mm",
                   "must be 0..2 mm, got " << subsurface_mm);
  SEWER3D_VALIDATE(subsurface_plastic_mm >= 0.0 && subsurface_plastic_mm <= 2.0,
                   "subsurface_plastic_mm", "must be 0..2 mm, got " << subsurface_plastic_mm);
  // A calibration this far off is no calibration (the decoder's tile choice needs the
  // epipolar geometry to a few pixels).
  SEWER3D_VALIDATE(calibration_focal_px >= 0.0 && calibration_focal_px <= 20.0,
                   "calibration_focal_px", "must be 0..20 px, got " << calibration_focal_px);
  SEWER3D_VALIDATE(calibration_centre_px >= 0.0 && calibration_centre_px <= 20.0,
                   "calibration_centre_px", "must be 0..20 px, got " << calibration_centre_px);
  SEWER3D_VALIDATE(calibration_baseline_mm >= 0.0 && calibration_baseline_mm <= 2.0,
                   "calibration_baseline_mm", "must be 0..2 mm, got " << calibration_baseline_mm);
  SEWER3D_VALIDATE(calibration_rotation_deg >= 0.0 && calibration_rotation_deg <= 1.0,
                   "calibration_rotation_deg",
                   "must be 0..1 deg, got " << calibration_rotation_deg);
  SEWER3D_VALIDATE(
      reference_width_px == 0 || (reference_width_px >= 64 && reference_width_px <= 20000),
      "reference_width_px",
      "must be 0 (the module's own pixels) or 64..20000 px, got " << reference_width_px);
  SEWER3D_VALIDATE(wavelength_nm >= 300.0 && wavelength_nm <= 2000.0, "speckle_wavelength_nm",
                   "must be 300..2000 nm, got " << wavelength_nm);
}

std::optional<SpotErrors> RealismProfile(const std::string& name) {
  if (name == "ideal") return SpotErrors{};
  if (name != "paper") return std::nullopt;
  // Tuned so that the five test scenes of the paper's tables land in (or within 30 % of) its
  // per-module ranges (docs/accuracy.md, "Realism"): the wall's relief gives the part
  // constant in millimetres, the spots' scatter on the image (placement, speckle) the part
  // that grows with the square of the distance. The relief is the paper's own constant part:
  // its five RMS figures read as RMS² = R² + (c z²)² give R = 0.055 mm (its test surfaces
  // are taken as mineral). Plastic pipe (PVC, PE) is smooth to micrometres: its hydraulic
  // roughness is 0.0015–0.007 mm.
  SpotErrors e;
  e.placement_sigma_px = 0.65;
  e.gain_sigma = 0.1;
  e.speckle_contrast = 0.1;
  e.lens_residual = 1e-4;
  e.relief_mm = 0.055;
  e.relief_plastic_mm = 0.005;
  // Concrete's cement paste scatters within tens of micrometres; plastic pipe more.
  e.subsurface_mm = 0.02;
  e.subsurface_plastic_mm = 0.15;
  // What calibrating a module with these errors from 20 board poses left (docs/calibration.md,
  // "paper" captures): focal lengths within a few tenths of a pixel, principal points half a
  // pixel, the projector's centre 0.015 mm and rotation 0.015 degrees per axis.
  e.calibration_focal_px = 0.3;
  e.calibration_centre_px = 0.5;
  e.calibration_baseline_mm = 0.015;
  e.calibration_rotation_deg = 0.015;
  // Pixels of the full-size module (2592 px): a smaller module errs by the same angles.
  e.reference_width_px = 2592;
  return e;
}

SpotErrors AtCameraWidth(const SpotErrors& errors, int camera_width) {
  if (errors.reference_width_px <= 0) return errors;
  const double scale = camera_width / static_cast<double>(errors.reference_width_px);
  SpotErrors e = errors;
  e.placement_sigma_px *= scale;
  e.calibration_focal_px *= scale;
  e.calibration_centre_px *= scale;
  e.reference_width_px = 0;
  return e;
}

SpotErrors ModuleOwnErrors(const SpotErrors& errors) {
  SpotErrors own = errors;
  own.relief_mm = own.relief_plastic_mm = 0.0;
  own.subsurface_mm = own.subsurface_plastic_mm = 0.0;
  own.calibration_focal_px = own.calibration_centre_px = 0.0;
  own.calibration_baseline_mm = own.calibration_rotation_deg = 0.0;
  return own;
}

Eigen::Vector2d ElementOffset(const SpotErrors& errors, int r, int c) {
  if (errors.placement_sigma_px <= 0.0) return Eigen::Vector2d::Zero();
  const std::uint64_t key = LatticeKey(r, c);
  return errors.placement_sigma_px * Eigen::Vector2d(HashNormal(errors.projector_seed, key, 1),
                                                     HashNormal(errors.projector_seed, key, 2));
}

double ElementGain(const SpotErrors& errors, int r, int c) {
  if (errors.gain_sigma <= 0.0) return 1.0;
  // Clamped so that no spot goes dark or negative (3.3 sigma at the largest sigma allowed).
  const double g = 1.0 + errors.gain_sigma * HashNormal(errors.projector_seed, LatticeKey(r, c), 3);
  return std::max(0.1, g);
}

LensResidual MakeLensResidual(const SpotErrors& errors, int lens) {
  if (errors.lens_residual <= 0.0) return {};
  // Directions of the decentring and thin-prism coefficient pairs.
  const auto which = static_cast<std::uint64_t>(lens);
  const double a = kTwoPi * HashUniform(errors.projector_seed, 21, which);
  const double b = kTwoPi * HashUniform(errors.projector_seed, 22, which);
  const double m = errors.lens_residual;
  return {m * std::cos(a), m * std::sin(a), m * std::cos(b), m * std::sin(b)};
}

Eigen::Vector2d LensResidual::ShiftPx(const CameraIntrinsics& k,
                                      const Eigen::Vector2d& pixel) const {
  const double x = (pixel.x() - k.cx) / k.fx, y = (pixel.y() - k.cy) / k.fy;
  const double r2 = x * x + y * y;
  // Brown–Conrady decentring and thin-prism terms (normalised coordinates).
  const double dx = 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x) + s1 * r2;
  const double dy = p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y + s2 * r2;
  return {k.fx * dx, k.fy * dy};
}

double ReliefMm(const SpotErrors& errors, Material material) {
  return IsPlastic(material) ? errors.relief_plastic_mm : errors.relief_mm;
}

double WallRelief(const SpotErrors& errors, Material material, std::uint64_t seed,
                  const Eigen::Vector2d& p_mm) {
  const double rms = ReliefMm(errors, material);
  if (rms <= 0.0) return 0.0;
  const Eigen::Vector2d q = p_mm / errors.relief_scale_mm;
  const double fx = std::floor(q.x()), fy = std::floor(q.y());
  const double tx = q.x() - fx, ty = q.y() - fy;
  const auto node = [&](double i, double j) {
    return HashNormal(seed + 0x4e11ef, LatticeKey(static_cast<int>(i), static_cast<int>(j)), 31);
  };
  const double h = (1 - tx) * (1 - ty) * node(fx, fy) + tx * (1 - ty) * node(fx + 1, fy) +
                   (1 - tx) * ty * node(fx, fy + 1) + tx * ty * node(fx + 1, fy + 1);
  // Bilinear weights average the lattice: E[Σ w²] = (2/3)², so the RMS is 2/3 before scaling.
  return rms * 1.5 * h;
}

double SubsurfaceMm(const SpotErrors& errors, Material material) {
  return IsPlastic(material) ? errors.subsurface_plastic_mm : errors.subsurface_mm;
}

ModuleDescription ActualModule(const ModuleDescription& calibrated, const SpotErrors& errors) {
  if (!errors.CalibrationError()) return calibrated;
  ModuleDescription m = calibrated;
  std::uint64_t draw = 40;
  const auto normal = [&](double sigma) {
    return sigma * HashNormal(errors.projector_seed, 0xca1b, draw++);
  };
  for (CameraIntrinsics* k : {&m.camera, &m.projector}) {
    k->fx += normal(errors.calibration_focal_px);
    k->fy += normal(errors.calibration_focal_px);
    k->cx += normal(errors.calibration_centre_px);
    k->cy += normal(errors.calibration_centre_px);
  }
  // The projector's centre (camera frame) and its rotation, each axis on its own.
  const Rigid3d camera_from_projector = calibrated.projector_from_camera.Inverse();
  Eigen::Vector3d centre = camera_from_projector.translation;
  Eigen::Vector3d angles;
  for (int i = 0; i < 3; ++i) centre[i] += normal(errors.calibration_baseline_mm);
  for (int i = 0; i < 3; ++i) angles[i] = DegToRad(normal(errors.calibration_rotation_deg));
  const Eigen::Matrix3d turn =
      (Eigen::AngleAxisd(angles.norm(), angles.norm() > 0 ? Eigen::Vector3d(angles.normalized())
                                                          : Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  m.projector_from_camera =
      Rigid3d(camera_from_projector.RotationMatrix() * turn, centre).Inverse();
  return m;
}

double SpeckleGrainPx(const SpotErrors& errors, double f_number, double pixel_pitch_mm) {
  // A pinhole camera (f-number 0) has no diffraction-limited grain: one pixel.
  const double grain_mm = 2.44 * errors.wavelength_nm * 1e-6 * f_number;
  return std::max(1.0, grain_mm / pixel_pitch_mm);
}

void ApplySpeckle(cv::Mat1f& signal, const SpotErrors& errors, double grain_px,
                  std::uint64_t seed) {
  if (errors.speckle_contrast <= 0.0 || signal.empty()) return;
  // Circular complex Gaussian field low-passed to the grain; its squared magnitude is fully
  // developed speckle (exponential intensity, contrast 1), normalised to mean 1.
  cv::Mat1f re(signal.size()), im(signal.size());
  for (int v = 0; v < signal.rows; ++v) {
    for (int u = 0; u < signal.cols; ++u) {
      const std::uint64_t pixel = static_cast<std::uint64_t>(v) * signal.cols + u;
      re(v, u) = static_cast<float>(HashNormal(seed, pixel, 11));
      im(v, u) = static_cast<float>(HashNormal(seed, pixel, 12));
    }
  }
  // `grain_px` is the Airy diameter 2.44 λN; the intensity correlation's FWHM is about λN,
  // and an amplitude kernel of sigma s gives an intensity correlation of sigma s. Below half a
  // pixel the pixel integrates several grains: the field stays at half a pixel and its
  // contrast falls in proportion (pixel area over grain area, square-rooted).
  const double wanted = grain_px / (2.44 * 2.355);
  const double sigma = std::max(0.5, wanted);
  const double contrast = errors.speckle_contrast * std::min(1.0, wanted / 0.5);
  cv::GaussianBlur(re, re, cv::Size(), sigma, sigma, cv::BORDER_REFLECT);
  cv::GaussianBlur(im, im, cv::Size(), sigma, sigma, cv::BORDER_REFLECT);
  cv::Mat1f intensity = re.mul(re) + im.mul(im);
  intensity /= std::max(1e-12, cv::mean(intensity)[0]);
  const auto c = static_cast<float>(contrast);
  signal = signal.mul(1.0f - c + c * intensity);
}

}  // namespace sewer3d
