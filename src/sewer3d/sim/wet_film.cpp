#include "sewer3d/sim/wet_film.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

double SchlickFresnel(const WetFilmOptions& film, double cos_theta) {
  const double r = (film.refractive_index - 1.0) / (film.refractive_index + 1.0);
  const double f0 = r * r;
  return f0 + (1.0 - f0) * std::pow(1.0 - std::clamp(cos_theta, 0.0, 1.0), 5);
}

// Smith's masking of one direction at cosine c for GGX roughness a.
double SmithG1(double a, double c) {
  return 2.0 * c / (c + std::sqrt(a * a + (1.0 - a * a) * c * c));
}

}  // namespace

void WetFilmOptions::Check() const {
  SEWER3D_VALIDATE(
      roughness >= 0.005 && roughness <= 1.0, "wet_film_roughness",
      "must be 0.005..1 (GGX α; below, the lobe is a mirror no sample meets), got " << roughness);
  SEWER3D_VALIDATE(refractive_index >= 1.0 && refractive_index <= 3.0, "wet_film_refractive_index",
                   "must be 1..3, got " << refractive_index);
  SEWER3D_VALIDATE(darkening >= 0.0 && darkening < 1.0, "wet_film_darkening",
                   "must be 0..1 (a fraction of the dry albedo), got " << darkening);
}

double FilmBrdf(const WetFilmOptions& film, const Eigen::Vector3d& n,
                const Eigen::Vector3d& to_light, const Eigen::Vector3d& to_eye) {
  const double cos_in = n.dot(to_light), cos_out = n.dot(to_eye);
  if (cos_in <= 0.0 || cos_out <= 0.0) return 0.0;
  const Eigen::Vector3d half = (to_light + to_eye).normalized();
  const double a2 = film.roughness * film.roughness;
  const double nh = n.dot(half);
  const double q = nh * nh * (a2 - 1.0) + 1.0;
  const double distribution = a2 / (std::numbers::pi * q * q);
  const double masking = SmithG1(film.roughness, cos_in) * SmithG1(film.roughness, cos_out);
  return SchlickFresnel(film, half.dot(to_eye)) * distribution * masking / (4.0 * cos_in * cos_out);
}

double FilmAmbientReflectance(const WetFilmOptions& film, double cos_eye) {
  return SchlickFresnel(film, cos_eye);
}

}  // namespace sewer3d
