#include "sewer3d/sim/renderer.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/material.hpp"

namespace sewer3d {
namespace {

constexpr double kReferenceDistanceMm = 150.0;
// A surface nearer to the projector than the lit point by more than this along the projector's
// ray hides it (the relief moves points off the smooth surface by up to a few tenths).
constexpr double kShadowToleranceMm = 0.5;

// Thin-lens circle of confusion (diameter, px) of a point at depth z for a lens focused at
// focus_mm with focal length f_px (pixels) and aperture diameter aperture_mm.
double CircleOfConfusionPx(double f_px, double aperture_mm, double focus_mm, double z_mm) {
  return f_px * aperture_mm * std::abs(1.0 / z_mm - 1.0 / focus_mm);
}

// Everything fixed for one frame.
struct Setup {
  const ModuleDescription& module;
  const BinaryArray& pattern;
  const Surface& surface;
  const RenderOptions& o;
  CameraModel camera, projector;
  Eigen::Matrix3d projector_rotation;
  Eigen::Vector3d projector_centre;  // camera frame, rig at rest
  double camera_aperture_mm, projector_aperture_mm;
  LensResidual camera_residual, projector_residual;  // what the module's lens model lacks
  cv::Mat2d corner_rays;  // normalised (x, y) at pixel corners; NaN where not invertible

  Setup(const ModuleDescription& m, const BinaryArray& p, const Surface& s,
        const RenderOptions& opt)
      : module(m),
        pattern(p),
        surface(s),
        o(opt),
        camera(m.camera),
        projector(m.projector),
        projector_rotation(m.projector_from_camera.RotationMatrix()),
        projector_centre(m.projector_from_camera.Inverse().translation),
        camera_residual(MakeLensResidual(opt.spot_errors, 0)),
        projector_residual(MakeLensResidual(opt.spot_errors, 1)) {
    const double pitch_mm = o.sensor_width_mm / m.camera.width;
    camera_aperture_mm = o.camera_f_number > 0 ? m.camera.fx * pitch_mm / o.camera_f_number : 0.0;
    projector_aperture_mm =
        o.projector_f_number > 0 ? m.projector.fx * pitch_mm / o.projector_f_number : 0.0;
    corner_rays.create(m.camera.height + 1, m.camera.width + 1);
    for (int v = 0; v <= m.camera.height; ++v) {
      for (int u = 0; u <= m.camera.width; ++u) {
        const Eigen::Vector2d corner(u - 0.5, v - 0.5);
        const auto xy = camera.Unproject(corner + camera_residual.ShiftPx(m.camera, corner));
        corner_rays(v, u) = xy ? cv::Vec2d(xy->x(), xy->y()) : cv::Vec2d(NAN, NAN);
      }
    }
  }

  // Spot irradiance profile at a projector pixel: tiled disks blurred by optics and defocus.
  double SpotProfile(const Eigen::Vector2d& uv, double sigma_px) const {
    const PatternLayout& layout = module.pattern;
    const double radius = 0.5 * layout.spot_diameter_px;
    const double reach = radius + 4.0 * sigma_px + 4.0 * o.spot_errors.placement_sigma_px;
    const int c_lo = static_cast<int>(
        std::floor((uv.x() - layout.offset_px.x() + 0.5 - reach) / layout.pitch_px - 0.5));
    const int c_hi = static_cast<int>(
        std::ceil((uv.x() - layout.offset_px.x() + 0.5 + reach) / layout.pitch_px - 0.5));
    const int r_lo = static_cast<int>(
        std::floor((uv.y() - layout.offset_px.y() + 0.5 - reach) / layout.pitch_px - 0.5));
    const int r_hi = static_cast<int>(
        std::ceil((uv.y() - layout.offset_px.y() + 0.5 + reach) / layout.pitch_px - 0.5));
    double value = 0.0;
    const double inv = 1.0 / (std::sqrt(2.0) * sigma_px);
    // The erfc edge holds π (R² + σ²) of light where the disk sends π R²: scaled back, so
    // that defocus and scattering spread a spot's light without adding to it.
    const double keep = radius * radius / (radius * radius + sigma_px * sigma_px);
    for (int r = r_lo; r <= r_hi; ++r) {
      for (int c = c_lo; c <= c_hi; ++c) {
        if (!pattern.tiled(r, c)) continue;
        const Eigen::Vector2d centre =
            layout.ElementCentre(r, c) + ElementOffset(o.spot_errors, r, c);
        const double rho2 = (uv - centre).squaredNorm();
        if (rho2 > reach * reach) continue;  // erfc below 3e-8
        const double rho = std::sqrt(rho2);
        // Disk edge convolved with a Gaussian.
        value += keep * ElementGain(o.spot_errors, r, c) * 0.5 * std::erfc((rho - radius) * inv);
      }
    }
    return value;  // overlapping spots add up (none do at the default pitch)
  }
};

// The projector's own line of sight: a point that a nearer surface hides from the projector
// (the bottom of a joint's gap behind its edge, the wall behind an intrusion) gets no pattern
// light, however the camera sees it.
bool InProjectorShadow(const Surface& surface, const Eigen::Vector3d& projector_centre,
                       const Eigen::Vector3d& point) {
  const Eigen::Vector3d ray = point - projector_centre;
  const auto blocker = surface.Intersect(projector_centre, ray);
  return blocker && blocker->t < 1.0 - kShadowToleranceMm / ray.norm();
}

// The water film at a hit seen from `to_eye` (unit): dry, it changes nothing.
struct Film {
  const WetFilmOptions& options;
  const SurfaceHit& hit;
  Eigen::Vector3d to_eye;
  double diffuse_gain = 1.0;  // of the albedo
  double ambient = 0.0;       // signal per ambient level
  Film(const WetFilmOptions& o, const SurfaceHit& h, const Eigen::Vector3d& eye)
      : options(o), hit(h), to_eye(eye) {
    if (h.film <= 0.0) return;
    diffuse_gain = 1.0 - o.darkening * h.film;
    ambient = 2.0 * h.film * FilmAmbientReflectance(o, std::max(0.0, h.normal.dot(eye)));
  }
  // Signal per unit of a light's level arriving from `to_light` (unit).
  [[nodiscard]] double Specular(const Eigen::Vector3d& to_light) const {
    if (hit.film <= 0.0) return 0.0;
    return 2.0 * std::numbers::pi * hit.film * FilmBrdf(options, hit.normal, to_light, to_eye);
  }
};

struct Sample {
  double pattern = 0.0;
  Eigen::Vector3d texture = Eigen::Vector3d::Zero();
  Eigen::Vector3d albedo = Eigen::Vector3d::Zero();  // of the surface hit
  int hits = 0;
};

// The ring light's radiant intensity (RGB, 1 on the axis's white) toward a direction whose
// cosine with the camera axis is cos_theta: cos^n falloff, colour from bluish to warm.
Eigen::Vector3d RingLight(const RenderOptions& o, double cos_theta) {
  const double t = (1.0 - cos_theta) / (1.0 - std::sqrt(0.5));
  const double shift = o.ring_light_color_shift * (t - 0.35);
  return std::pow(cos_theta, o.ring_light_exponent) *
         Eigen::Vector3d(1.0 + shift, 1.0, 1.0 - shift);
}

Sample Shade(const Setup& s, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
             const Eigen::Vector3d& rig_shift, double cos_alpha) {
  Sample out;
  auto hit = s.surface.Intersect(origin, direction);
  if (!hit) return out;
  out.hits = 1;
  const RenderOptions& o = s.o;
  if (ReliefMm(o.spot_errors, hit->material) > 0.0) {
    // The micro-relief as a height field over the smooth wall: the ray meets it h / cos θ
    // earlier along the ray (slopes of the relief are small).
    const double h =
        WallRelief(o.spot_errors, hit->material, s.surface.MaterialSeed(), hit->surface_mm);
    const Eigen::Vector3d d = direction.normalized();
    const double cos_theta = std::max(0.2, std::abs(hit->normal.dot(d)));
    hit->point -= d * (h / cos_theta);
  }
  const Eigen::Vector3d albedo =
      hit->albedo.allFinite()
          ? hit->albedo
          : MaterialAlbedo(hit->material, s.surface.MaterialSeed(), hit->surface_mm);
  // A water film darkens the wall and adds its specular lobe; in signal units a diffuse
  // albedo a gives a / 0.5 of a light's level, a BRDF f gives 2π f of it. The truth albedo
  // is the wall's as it is, wet or dry (the gloss is light, not colour).
  const Film film(o.wet_film, *hit, (origin - hit->point).normalized());
  out.albedo = albedo * film.diffuse_gain;
  const Eigen::Vector3d diffuse = albedo * film.diffuse_gain / 0.5;
  const double grey = albedo.mean() * film.diffuse_gain;
  const double vignetting = o.vignetting ? std::pow(cos_alpha, 4) : 1.0;
  if (o.images != RenderImages::kPattern) {
    // Texture light: a ring around the camera pupil, treated as a point source there whose
    // intensity and colour depend on the emission angle (the ring's axis is the camera's).
    const Eigen::Vector3d to_light = rig_shift - hit->point;
    const double d_light = to_light.norm();
    const double cos_light = std::max(0.0, hit->normal.dot(to_light) / d_light);
    const double falloff = std::pow(kReferenceDistanceMm / d_light, 2) * cos_light;
    const Eigen::Vector3d light = o.texture_level * falloff * RingLight(o, -to_light.z() / d_light);
    out.texture = diffuse.cwiseProduct(light + Eigen::Vector3d::Constant(o.ambient_level)) +
                  film.Specular(to_light / d_light) * light +
                  Eigen::Vector3d::Constant(film.ambient * o.ambient_level);
    if (o.vignetting) {
      const Eigen::Vector3d shading(std::pow(cos_alpha, 4 + o.color_shading.x()),
                                    std::pow(cos_alpha, 4 + o.color_shading.y()),
                                    std::pow(cos_alpha, 4 + o.color_shading.z()));
      out.texture = out.texture.cwiseProduct(shading);
    }
    out.texture = out.texture.cwiseProduct(o.white_balance);
  }
  if (o.images == RenderImages::kTexture) return out;
  // Pattern light from the projector.
  const Eigen::Vector3d p_rig = hit->point - rig_shift;
  const Eigen::Vector3d p_projector =
      s.projector_rotation * p_rig + s.module.projector_from_camera.translation;
  double pattern = o.ambient_level, specular = o.ambient_level * film.ambient;
  const auto uv = s.projector.Project(p_projector);
  const auto& pi = s.module.projector;
  if (uv && uv->x() >= -0.5 && uv->y() >= -0.5 && uv->x() <= pi.width - 0.5 &&
      uv->y() <= pi.height - 0.5) {
    const Eigen::Vector3d projector_centre = s.projector_centre + rig_shift;
    const Eigen::Vector3d to_projector = projector_centre - hit->point;
    const double d_projector = to_projector.norm();
    const double cos_in = std::max(0.0, hit->normal.dot(to_projector) / d_projector);
    const double cos_beta = p_projector.z() / p_projector.norm();
    const double coc = s.projector_aperture_mm > 0
                           ? CircleOfConfusionPx(s.module.projector.fx, s.projector_aperture_mm,
                                                 o.projector_focus_mm, p_projector.z())
                           : 0.0;
    // Subsurface scattering spreads the spot on the wall: its sigma across the ray, in
    // projector px at this distance.
    const double scatter_px =
        SubsurfaceMm(o.spot_errors, hit->material) * s.module.projector.fx / p_projector.z();
    const double sigma = std::sqrt(o.projector_psf_px * o.projector_psf_px +
                                   std::pow(coc / 2.5, 2) + scatter_px * scatter_px);
    const double lens = o.vignetting ? std::pow(cos_beta, 4) : 1.0;
    const Eigen::Vector2d element_uv = *uv + s.projector_residual.ShiftPx(pi, *uv);
    const double spot = s.SpotProfile(element_uv, sigma);
    if (spot > 0.0 && !InProjectorShadow(s.surface, projector_centre, hit->point)) {
      const double irradiance =
          o.pattern_level * spot * lens * std::pow(kReferenceDistanceMm / d_projector, 2) * cos_in;
      pattern += irradiance;
      specular += film.Specular(to_projector / d_projector) * irradiance;
    }
  }
  out.pattern = ((grey / 0.5) * pattern + specular) * vignetting;
  return out;
}

// Motion blur of a frame rendered with one sample per pixel: each pixel averages the sharp
// signal along the image path of its 3-D point over the exposure (the camera moves by `motion`,
// camera frame, so the point by −motion), bilinear samples every quarter pixel. Pixels without
// depth keep their value.
void BlurAlongMotion(const CameraModel& camera, const cv::Mat1f& depth,
                     const Eigen::Vector3d& motion, RenderedFrame& frame) {
  const cv::Mat1f pattern = frame.pattern_signal.clone();
  const cv::Mat3f texture = frame.texture_signal.clone();
  tbb::parallel_for(0, depth.rows, [&](int v) {
    for (int u = 0; u < depth.cols; ++u) {
      const float z = depth(v, u);
      const auto xy = camera.Unproject({double(u), double(v)});
      if (!std::isfinite(z) || !xy) continue;
      const Eigen::Vector3d p = double(z) * Eigen::Vector3d(xy->x(), xy->y(), 1.0);
      const auto a = camera.Project(p + 0.5 * motion), b = camera.Project(p - 0.5 * motion);
      if (!a || !b) continue;
      const Eigen::Vector2d d = *b - *a;
      // Quarter-pixel steps, at most as many as for a smear across the whole image.
      const double longest = 4.0 * std::hypot(depth.cols, depth.rows);
      const int steps =
          std::max(2, static_cast<int>(std::ceil(std::min(d.norm() / 0.25, longest))));
      double sum_pattern = 0.0;
      cv::Vec3d sum_texture(0, 0, 0);
      for (int i = 0; i < steps; ++i) {
        const Eigen::Vector2d q = Eigen::Vector2d(u, v) + d * ((i + 0.5) / steps - 0.5);
        // Bilinear, the border clamped.
        const double x = std::clamp(q.x(), 0.0, depth.cols - 1.0);
        const double y = std::clamp(q.y(), 0.0, depth.rows - 1.0);
        const int x0 = std::min(static_cast<int>(x), depth.cols - 2);
        const int y0 = std::min(static_cast<int>(y), depth.rows - 2);
        const double fx = x - x0, fy = y - y0;
        const double w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy,
                     w11 = fx * fy;
        sum_pattern += w00 * pattern(y0, x0) + w10 * pattern(y0, x0 + 1) +
                       w01 * pattern(y0 + 1, x0) + w11 * pattern(y0 + 1, x0 + 1);
        sum_texture += w00 * cv::Vec3d(texture(y0, x0)) + w10 * cv::Vec3d(texture(y0, x0 + 1)) +
                       w01 * cv::Vec3d(texture(y0 + 1, x0)) +
                       w11 * cv::Vec3d(texture(y0 + 1, x0 + 1));
      }
      frame.pattern_signal(v, u) = static_cast<float>(sum_pattern / steps);
      frame.texture_signal(v, u) = cv::Vec3f(sum_texture / steps);
    }
  });
}

}  // namespace

void RenderOptions::Check() const {
  // Upper bounds are far beyond any real module; beyond them the images are pure noise or
  // saturation, or the blur kernels make rendering run for hours.
  const auto within = [](const char* field, double value, double low, double high) {
    SEWER3D_VALIDATE(value >= low && value <= high, field,
                     "must be " << low << ".." << high << ", got " << value);
  };
  SEWER3D_VALIDATE(supersampling >= 1 && supersampling <= 16, "supersampling",
                   "must be 1..16, got " << supersampling);
  // It sets the pixel pitch, so the apertures' blur: the smallest camera chips are about 1 mm
  // wide, the largest 40.
  within("sensor_width_mm", sensor_width_mm, 0.5, 100.0);
  // 0: a pinhole (RenderOptions::Ideal); a lens is f/0.5 or slower.
  for (const auto& [field, f_number] : {std::pair{"camera_f_number", camera_f_number},
                                        std::pair{"projector_f_number", projector_f_number}}) {
    SEWER3D_VALIDATE(f_number == 0.0 || (f_number >= 0.5 && f_number <= 64.0), field,
                     "must be 0 (a pinhole) or 0.5..64, got " << f_number);
  }
  SEWER3D_VALIDATE(camera_focus_mm > 0.0 && camera_focus_mm <= 1e5, "camera_focus_mm",
                   "must be > 0 and at most 1e5 mm, got " << camera_focus_mm);
  SEWER3D_VALIDATE(projector_focus_mm > 0.0 && projector_focus_mm <= 1e5, "projector_focus_mm",
                   "must be > 0 and at most 1e5 mm, got " << projector_focus_mm);
  SEWER3D_VALIDATE(projector_psf_px > 0.0 && projector_psf_px <= 20.0, "projector_psf_px",
                   "must be > 0 and at most 20 px, got " << projector_psf_px);
  // Levels are fractions of the sensor's full scale for a white wall at the reference.
  within("texture_level", texture_level, 0.0, 10.0);
  SEWER3D_VALIDATE(pattern_level > 0.0 && pattern_level <= 10.0, "pattern_level",
                   "must be > 0 (0 projects no spots) and at most 10, got " << pattern_level);
  // The light of a sewer without the module's own: above full scale every pixel saturates.
  SEWER3D_VALIDATE(ambient_level >= 0.0 && ambient_level <= 1.0, "ambient_level",
                   "must be 0..1 (a fraction of the sensor's full scale; above 1 every pixel "
                   "saturates), got "
                       << ambient_level);
  within("ring_light_exponent", ring_light_exponent, 0.0, 16.0);
  SEWER3D_VALIDATE(std::abs(ring_light_color_shift) <= 0.5, "ring_light_color_shift",
                   "must be within ±0.5, got " << ring_light_color_shift);
  SEWER3D_VALIDATE(color_shading.minCoeff() >= 0.0 && color_shading.maxCoeff() <= 8.0,
                   "color_shading", "must be 0..8 per channel");
  SEWER3D_VALIDATE(white_balance.minCoeff() > 0.0 && white_balance.maxCoeff() <= 4.0,
                   "white_balance", "gains must be in (0, 4]");
  within("speed_mm_s", speed_mm_s, 0.0, 10000.0);
  within("exposure_ms", exposure_ms, 0.0, 1000.0);
  // Beyond, a pixel averages a smear longer than the view (and the blur's samples grow with
  // it: 10 m took over 5 minutes for one frame).
  constexpr double kMaxMotionMm = 50.0;
  SEWER3D_VALIDATE(speed_mm_s * exposure_ms * 1e-3 <= kMaxMotionMm, "speed_mm_s",
                   "times exposure_ms: the rig would move " << speed_mm_s * exposure_ms * 1e-3
                                                            << " mm during the exposure; at most "
                                                            << kMaxMotionMm << " mm");
  SEWER3D_VALIDATE(motion_direction.allFinite() && motion_direction.norm() > 0.0 &&
                       std::isfinite(motion_direction.norm()),
                   "motion_direction", "must be a finite, non-zero direction");
  spot_errors.Check();
  wet_film.Check();
  SEWER3D_VALIDATE(sensor.bits >= 8 && sensor.bits <= 12, "bits",
                   "must be 8..12, got " << sensor.bits);
  SEWER3D_VALIDATE(sensor.full_well_e > 0.0 && sensor.full_well_e <= 1e7, "full_well_e",
                   "must be > 0 and at most 1e7 electrons, got " << sensor.full_well_e);
  SEWER3D_VALIDATE(
      sensor.read_noise_e >= 0.0 && sensor.read_noise_e <= sensor.full_well_e, "read_noise_e",
      "must be 0..full_well_e (" << sensor.full_well_e << "), got " << sensor.read_noise_e);
}

RenderOptions RenderOptions::Ideal() {
  RenderOptions o;
  o.camera_f_number = 0.0;
  o.projector_f_number = 0.0;
  o.ambient_level = 0.0;
  o.vignetting = false;
  o.ring_light_color_shift = 0.0;
  o.sensor.noise = false;
  o.supersampling = 4;
  return o;
}

RenderedFrame RenderFrame(const ModuleDescription& module, const BinaryArray& pattern,
                          const Scene& scene, const RenderOptions& o) {
  scene.Check();
  return RenderFrame(module, pattern, SceneSurface(scene), o);
}

RenderedFrame RenderFrame(const ModuleDescription& calibrated, const BinaryArray& pattern,
                          const Surface& surface, const RenderOptions& options) {
  calibrated.Check();
  options.Check();
  RenderOptions o = options;
  o.spot_errors = AtCameraWidth(options.spot_errors, calibrated.camera.width);
  // The module file is the calibrated module; the scene is lit and seen by the actual one.
  const ModuleDescription module = ActualModule(calibrated, o.spot_errors);
  const Setup setup(module, pattern, surface, o);
  const int w = module.camera.width, h = module.camera.height, n = o.supersampling;
  RenderedFrame frame;
  frame.pattern_signal.create(h, w);
  frame.texture_signal.create(h, w);
  frame.pattern.create(h, w);
  frame.texture.create(h, w);
  frame.truth_depth.create(h, w);
  if (o.truth_albedo) frame.truth_albedo.create(h, w);
  const Eigen::Vector3d motion =
      o.motion_direction.normalized() * (o.speed_mm_s * o.exposure_ms * 1e-3);
  // One sample per pixel cannot sample the exposure: the motion blur is applied to the
  // rendered signal instead (BlurAlongMotion).
  const bool blur_after = n == 1 && motion.norm() > 0.0;

  tbb::parallel_for(0, h, [&](int v) {
    for (int u = 0; u < w; ++u) {
      const std::uint64_t pixel = static_cast<std::uint64_t>(v) * w + u;
      const Eigen::Vector2d centre(u, v);  // what the pixel sees, with the lens's residual
      const auto centre_ray =
          setup.camera.Unproject(centre + setup.camera_residual.ShiftPx(module.camera, centre));
      float depth = NAN;
      if (centre_ray && (o.truth_depth || blur_after)) {
        const auto hit = surface.Intersect(Eigen::Vector3d::Zero(),
                                           Eigen::Vector3d(centre_ray->x(), centre_ray->y(), 1.0));
        if (hit) depth = static_cast<float>(hit->point.z());
      }
      frame.truth_depth(v, u) = depth;
      const cv::Vec2d c00 = setup.corner_rays(v, u), c10 = setup.corner_rays(v, u + 1);
      const cv::Vec2d c01 = setup.corner_rays(v + 1, u), c11 = setup.corner_rays(v + 1, u + 1);
      Sample sum;
      if (std::isfinite(c00[0] + c10[0] + c01[0] + c11[0])) {
        for (int k = 0; k < n * n; ++k) {
          // Stratified position in the pixel; the aperture sample uses a scrambled stratum.
          const double sx = (k % n + HashUniform(o.seed, pixel, k, 1)) / n;
          // NOLINTNEXTLINE(bugprone-integer-division): k / n is the stratum's row, an integer
          const double sy = (k / n + HashUniform(o.seed, pixel, k, 2)) / n;
          const cv::Vec2d xy =
              (1 - sx) * (1 - sy) * c00 + sx * (1 - sy) * c10 + (1 - sx) * sy * c01 + sx * sy * c11;
          Eigen::Vector3d direction(xy[0], xy[1], 1.0);
          const double cos_alpha = 1.0 / direction.norm();
          // The instant uses its own scrambled stratum (step n + 1, coprime to n²): tied to k
          // it would follow the sub-pixel row and lengthen the blur along v by about a pixel.
          const int kt =
              (static_cast<int>(HashUniform(o.seed, pixel, 8) * n * n) + k * (n + 1)) % (n * n);
          const double tau = n * n > 1 ? (kt + HashUniform(o.seed, pixel, k, 3)) / (n * n) : 0.5;
          const Eigen::Vector3d shift = motion * (tau - 0.5);
          Eigen::Vector3d origin = shift;
          if (setup.camera_aperture_mm > 0.0) {
            // Thin lens: rays through the aperture converge on the plane of focus.
            const int kk = static_cast<int>(HashUniform(o.seed, pixel, 7) * n * n + k) % (n * n);
            const double radius = 0.5 * setup.camera_aperture_mm *
                                  std::sqrt((kk % n + HashUniform(o.seed, pixel, k, 4)) / n);
            // NOLINTNEXTLINE(bugprone-integer-division): kk / n is the stratum's ring, an integer
            const double angle = kTwoPi * (kk / n + HashUniform(o.seed, pixel, k, 5)) / n;
            const Eigen::Vector3d lens(radius * std::cos(angle), radius * std::sin(angle), 0.0);
            const Eigen::Vector3d focus = direction * o.camera_focus_mm;
            origin += lens;
            direction = focus - lens;
          }
          const Sample s = Shade(setup, origin, direction, shift, cos_alpha);
          sum.pattern += s.pattern;
          sum.texture += s.texture;
          sum.albedo += s.albedo;
          sum.hits += s.hits;
        }
      }
      const double pattern_signal = sum.pattern / (n * n);
      const Eigen::Vector3d texture_signal = sum.texture / (n * n);
      frame.pattern_signal(v, u) = static_cast<float>(pattern_signal);
      frame.texture_signal(v, u) =
          cv::Vec3f(texture_signal.x(), texture_signal.y(), texture_signal.z());
      if (o.truth_albedo) {
        const Eigen::Vector3d albedo = sum.albedo / sum.hits;  // NaN when no sample hit
        frame.truth_albedo(v, u) =
            sum.hits > 0 ? cv::Vec3f(albedo.x(), albedo.y(), albedo.z()) : cv::Vec3f(NAN, NAN, NAN);
      }
    }
  });
  if (blur_after) BlurAlongMotion(setup.camera, frame.truth_depth, motion, frame);
  if (o.images != RenderImages::kTexture) {
    const double pixel_pitch_mm = o.sensor_width_mm / w;
    ApplySpeckle(frame.pattern_signal, o.spot_errors,
                 SpeckleGrainPx(o.spot_errors, o.camera_f_number, pixel_pitch_mm), o.seed + 0x5eed);
  }
  if (!o.truth_depth) frame.truth_depth.setTo(NAN);
  tbb::parallel_for(0, h, [&](int v) {
    for (int u = 0; u < w; ++u) {
      const std::uint64_t pixel = static_cast<std::uint64_t>(v) * w + u;
      const cv::Vec3f t = frame.texture_signal(v, u);
      frame.pattern(v, u) = o.images == RenderImages::kTexture
                                ? 0
                                : Digitise(frame.pattern_signal(v, u), o.sensor, o.seed, pixel, 0);
      frame.texture(v, u) = o.images == RenderImages::kPattern
                                ? cv::Vec3w(0, 0, 0)
                                : cv::Vec3w(Digitise(t[0], o.sensor, o.seed, pixel, 1),
                                            Digitise(t[1], o.sensor, o.seed, pixel, 2),
                                            Digitise(t[2], o.sensor, o.seed, pixel, 3));
    }
  });
  if (o.sensor.color_filter == ColorFilter::kRggb && o.images != RenderImages::kPattern)
    frame.texture_raw = MosaicRggb(frame.texture);
  frame.samples = static_cast<std::int64_t>(w) * h * n * n;
  return frame;
}

}  // namespace sewer3d
