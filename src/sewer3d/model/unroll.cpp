#include "sewer3d/model/unroll.hpp"

#include <cmath>
#include <numbers>

namespace sewer3d {

double WrapClock(double clock_rad) {
  constexpr double kTurn = 2.0 * std::numbers::pi;
  double c = std::fmod(clock_rad, kTurn);
  if (c < 0.0) c += kTurn;
  return c >= kTurn ? 0.0 : c;
}

CylPoint Unroll(const Centreline& centreline, const Eigen::Vector3d& p_model,
                double station_guess_mm) {
  double s = station_guess_mm;
  AxisFrame f = centreline.FrameAt(s);
  // f(s) = (p − o(s))·t(s) has slope −1 + ρκ: the fixed-point step s + f(s) converges at rate
  // ρκ; a secant step on the last two iterates then makes it quadratic.
  double prev_s = s, prev_f = (p_model - f.origin).dot(f.tangent);
  s += prev_f;
  for (int iteration = 0; iteration < 50; ++iteration) {
    f = centreline.FrameAt(s);
    const double r = (p_model - f.origin).dot(f.tangent);
    if (std::abs(r) < 1e-9) break;
    const double slope = (r - prev_f) / (s - prev_s);
    const double step = (slope < -0.5 && slope > -2.0) ? -r / slope : r;
    prev_s = s, prev_f = r;
    s += step;
  }
  const Eigen::Vector3d v = p_model - f.origin;
  CylPoint cyl;
  cyl.station_mm = s;
  cyl.clock_rad = WrapClock(std::atan2(v.dot(f.right), v.dot(f.crown)));
  cyl.radius_mm = (v - v.dot(f.tangent) * f.tangent).norm();
  return cyl;
}

Eigen::Vector3d PointAt(const Centreline& centreline, const CylPoint& cyl) {
  const AxisFrame f = centreline.FrameAt(cyl.station_mm);
  return f.origin + cyl.radius_mm * f.Direction(cyl.clock_rad);
}

}  // namespace sewer3d
