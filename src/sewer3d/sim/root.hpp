#pragma once
/// \file
/// Bracketed root refinement shared by the surfaces' ray intersections.

#include <cmath>

namespace sewer3d {

/// Root of g in [a, b] with g(a) <= 0 < g(b), by the Illinois variant of regula falsi
/// (superlinear, and safe on the steps of displaced walls). Returns the last estimate after
/// the bracket is narrower than `tolerance` or 60 iterations.
template <typename F>
double IllinoisRoot(const F& g, double a, double b, double ga, double gb, double tolerance) {
  int side = 0;
  double t = a;
  for (int it = 0; it < 60 && b - a > tolerance; ++it) {
    t = (a * gb - b * ga) / (gb - ga);
    if (!(t > a && t < b)) t = 0.5 * (a + b);
    const double gt = g(t);
    if (gt > 0.0) {
      b = t, gb = gt;
      if (side == -1) ga *= 0.5;
      side = -1;
    } else {
      a = t, ga = gt;
      if (side == 1) gb *= 0.5;
      side = 1;
    }
    if (std::abs(gt) < 1e-10) break;
  }
  return t;
}

}  // namespace sewer3d
