#include "sewer3d/sim/wet_film.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

const Eigen::Vector3d kNormal = Eigen::Vector3d::UnitZ();

Eigen::Vector3d Direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// Water reflects ((n − 1) / (n + 1))² = 2.0 % at normal incidence.
double F0() { return std::pow(0.33 / 2.33, 2); }

TEST(WetFilm, TheMirrorDirectionHasTheLobesPeak) {
  const WetFilmOptions film;
  // At normal incidence and view, GGX's peak 1 / (π α²) with no masking: F0 / (4 π α²).
  EXPECT_NEAR(FilmBrdf(film, kNormal, kNormal, kNormal), F0() / (4.0 * std::numbers::pi * 0.01),
              1e-9);
  // Mirror pairs off the normal still meet the peak's distribution; off the mirror it falls.
  const Eigen::Vector3d in = Direction(0.3, 0.0), out = Direction(0.3, std::numbers::pi);
  // Turning the view by 4α turns the half-vector by about 2α: GGX falls to (1 + 4α²)² / 25.
  const Eigen::Vector3d off = Direction(0.3 + 4.0 * 0.1, std::numbers::pi);
  EXPECT_GT(FilmBrdf(film, kNormal, in, out), 10.0 * FilmBrdf(film, kNormal, in, off));
  // Reciprocal, and nothing from below the surface.
  EXPECT_DOUBLE_EQ(FilmBrdf(film, kNormal, in, off), FilmBrdf(film, kNormal, off, in));
  EXPECT_EQ(FilmBrdf(film, kNormal, -in, out), 0.0);
  EXPECT_EQ(FilmBrdf(film, kNormal, in, -out), 0.0);
}

// The lobe sends back what Fresnel reflects: ∫ f cos θ dω over the hemisphere is Schlick's
// reflectance at the viewing angle, less what masking takes (GGX's known loss: up to 15 % at
// 60° for α = 0.2), for a view along the normal and one at 60°.
TEST(WetFilm, TheLobeReflectsTheFresnelShare) {
  for (const double alpha : {0.05, 0.2}) {
    WetFilmOptions film;
    film.roughness = alpha;
    for (const double view : {0.0, std::numbers::pi / 3.0}) {
      const Eigen::Vector3d eye = Direction(view, 0.0);
      double sum = 0.0;
      const int n_theta = 1500, n_phi = 720;
      for (int i = 0; i < n_theta; ++i) {
        const double theta = (i + 0.5) * 0.5 * std::numbers::pi / n_theta;
        for (int j = 0; j < n_phi; ++j) {
          const double phi = (j + 0.5) * 2.0 * std::numbers::pi / n_phi;
          sum += FilmBrdf(film, kNormal, Direction(theta, phi), eye) * std::cos(theta) *
                 std::sin(theta);
        }
      }
      sum *= (0.5 * std::numbers::pi / n_theta) * (2.0 * std::numbers::pi / n_phi);
      const double fresnel = FilmAmbientReflectance(film, std::cos(view));
      EXPECT_GT(sum, 0.8 * fresnel) << alpha << " " << view;
      EXPECT_LT(sum, 1.05 * fresnel) << alpha << " " << view;
    }
  }
}

// A plane wet all over, facing the camera at 150 mm, with an albedo of its own.
class WetPlane final : public Surface {
 public:
  explicit WetPlane(double film) : film_(film) { plane_.distance_mm = 150.0; }
  std::optional<SurfaceHit> Intersect(const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction) const override {
    auto hit = sewer3d::Intersect(plane_, origin, direction);
    if (hit) {
      hit->albedo = Eigen::Vector3d::Constant(0.4);
      hit->film = film_;
    }
    return hit;
  }
  std::uint64_t MaterialSeed() const override { return 1; }

 private:
  Scene plane_;
  double film_;
};

// On the axis the ring light's mirror image: the texture signal is the darkened wall's plus
// the lobe's peak, 2π · F0 / (4π α²) of the light's level; off the lobe only the darkening.
TEST(WetFilm, TheRingLightsHighlightSitsOnTheAxis) {
  const ModuleDescription module = testing::SmallDefaultModule(648);
  RenderOptions o = RenderOptions::Ideal();
  o.images = RenderImages::kTexture;
  o.supersampling = 2;
  o.wet_film.roughness = 0.3;
  o.truth_albedo = true;
  const RenderedFrame dry = RenderFrame(module, DefaultPatternArray(), WetPlane(0.0), o);
  const RenderedFrame wet = RenderFrame(module, DefaultPatternArray(), WetPlane(1.0), o);
  const int u = static_cast<int>(std::round(module.camera.cx)),
            v = static_cast<int>(std::round(module.camera.cy));
  const double dry_centre = dry.texture_signal(v, u)[1];
  EXPECT_NEAR(dry_centre, 0.4 / 0.5 * o.texture_level, 0.002);
  const double peak = 2.0 * std::numbers::pi * F0() / (4.0 * std::numbers::pi * 0.09);
  EXPECT_NEAR(wet.texture_signal(v, u)[1], 0.65 * dry_centre + peak * o.texture_level, 0.002);
  // The truth albedo is the wet wall's (the gloss is light, not colour).
  EXPECT_NEAR(wet.truth_albedo(v, u)[1], 0.65 * 0.4, 1e-6);
  EXPECT_NEAR(dry.truth_albedo(v, u)[1], 0.4, 1e-6);
  // In a corner, far out on the lobe, it adds about 1 % to the darkened wall.
  const double dry_corner = dry.texture_signal(5, 5)[1], wet_corner = wet.texture_signal(5, 5)[1];
  EXPECT_GT(wet_corner, 0.65 * dry_corner);
  EXPECT_LT(wet_corner, 0.75 * dry_corner);
}

TEST(WetFilm, CheckNamesTheField) {
  WetFilmOptions film;
  film.roughness = 0.0;
  EXPECT_THROW(film.Check(), InvalidValue);
  film = {};
  film.darkening = 1.0;
  EXPECT_THROW(film.Check(), InvalidValue);
  RenderOptions o;
  o.wet_film.refractive_index = 0.5;
  try {
    o.Check();
    FAIL();
  } catch (const InvalidValue& e) {
    EXPECT_EQ(e.field(), "wet_film_refractive_index");
  }
}

}  // namespace
}  // namespace sewer3d
