#pragma once
/// \file
/// A water film over the wall (a wet patch, the wetted invert, condensation): a smooth
/// dielectric layer that adds a specular lobe to the wall's diffuse reflection and darkens it
/// (docs/simulator.md, "Wet patches"). Pure functions of directions; the renderer calls them.

#include <Eigen/Core>

namespace sewer3d {

struct WetFilmOptions {
  /// GGX roughness α of the film's surface: a film follows the wall's millimetre-scale
  /// undulation, so its highlight is a lobe of about ±α rad, not a mirror image.
  double roughness = 0.1;
  double refractive_index = 1.33;  ///< water: 2 % reflected at normal incidence
  /// A wall under full cover reflects diffusely (1 − darkening) of its dry albedo (wet
  /// concrete, sand and soil read 30–40 % darker: light trapped in the film is absorbed more).
  double darkening = 0.35;

  void Check() const;
};

/// Specular BRDF (sr⁻¹) of the film at unit normal `n` for unit directions from the surface
/// point to the light and to the eye: GGX microfacet distribution, separable Smith masking,
/// Schlick's Fresnel; 0 when either direction is below the surface.
double FilmBrdf(const WetFilmOptions& film, const Eigen::Vector3d& n,
                const Eigen::Vector3d& to_light, const Eigen::Vector3d& to_eye);

/// The film's reflectance of uniform light from the whole hemisphere toward the eye at cosine
/// `cos_eye` to the normal (Schlick's Fresnel at the viewing angle: the lobe integrates to it).
double FilmAmbientReflectance(const WetFilmOptions& film, double cos_eye);

}  // namespace sewer3d
