#include "sewer3d/sim/pipe_world.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/material.hpp"
#include "sewer3d/sim/root.hpp"

namespace sewer3d {
namespace {

// Centreline frame of a section in its own start frame at arc length u.
Rigid3d LocalFrame(const PipeSection& s, double u) {
  if (s.bend_radius_mm <= 0.0) return {Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, u)};
  const Eigen::Vector3d d = ClockDirection(ClockHoursToRad(s.bend_clock_h));
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ().cross(d);
  const Eigen::Quaterniond r(Eigen::AngleAxisd(u / s.bend_radius_mm, n));
  return {r, s.bend_radius_mm * (d - (r * d))};
}

// Arc length of the centreline point nearest to a point given in the section's start frame.
double LocalArc(const PipeSection& s, const Eigen::Vector3d& local) {
  if (s.bend_radius_mm <= 0.0) return local.z();
  const Eigen::Vector3d d = ClockDirection(ClockHoursToRad(s.bend_clock_h));
  const Eigen::Vector3d w = local - s.bend_radius_mm * d;
  return s.bend_radius_mm * std::atan2(w.dot(Eigen::Vector3d::UnitZ()), -w.dot(d));
}

Rigid3d Blend(const Rigid3d& a, const Rigid3d& b, double w) {
  return {a.rotation.slerp(w, b.rotation), (1.0 - w) * a.translation + w * b.translation};
}

}  // namespace

Eigen::Vector3d ClockDirection(double clock_rad) {
  return {std::sin(clock_rad), -std::cos(clock_rad), 0.0};
}

void PipeWorld::Check() const {
  // Field names as in the scenario file's "pipe" member (docs/formats.md).
  SEWER3D_VALIDATE(!sections.empty(), "sections", "the pipe needs at least one section");
  auto joints_text = [](size_t n) { return std::to_string(n) + (n == 1 ? " joint" : " joints"); };
  SEWER3D_VALIDATE(joints.size() + 1 == sections.size(), "joints",
                   sections.size()
                       << " sections need " << joints_text(sections.size() - 1)
                       << " (one between each pair), got " << joints_text(joints.size()));
  for (size_t i = 0; i < sections.size(); ++i) {
    const PipeSection& s = sections[i];
    const std::string field = "sections[" + std::to_string(i) + "].";
    ValidatePositive(field + "length_mm", s.length_mm);
    SEWER3D_VALIDATE(s.diameter_mm >= 50.0 && s.diameter_mm <= 5000.0, field + "diameter_mm",
                     "must be 50..5000, got " << s.diameter_mm);
    SEWER3D_VALIDATE(s.ovality_pct >= 0.0 && s.ovality_pct < 30.0, field + "ovality_pct",
                     "must be >= 0 and < 30, got " << s.ovality_pct);
    ValidateClockHours(field + "ovality_clock_h", s.ovality_clock_h);
    ValidateClockHours(field + "bend_clock_h", s.bend_clock_h);
    SEWER3D_VALIDATE(s.bend_radius_mm == 0.0 || s.bend_radius_mm >= 10.0 * s.diameter_mm,
                     field + "bend_radius_mm",
                     "must be 0 (straight) or at least 10 diameters ("
                         << 10.0 * s.diameter_mm << "), got " << s.bend_radius_mm);
  }
  SEWER3D_VALIDATE(LengthMm() <= kMaxLengthMm, "sections",
                   "the pipe is " << LengthMm() / 1000.0
                                  << " m long; a run between two manholes is at most "
                                  << kMaxLengthMm / 1000.0 << " m");
  for (size_t i = 0; i < joints.size(); ++i) {
    const PipeJoint& j = joints[i];
    const std::string field = "joints[" + std::to_string(i) + "].";
    ValidateNotNegative(field + "gap_mm", j.gap_mm);
    ValidateNotNegative(field + "gap_depth_mm", j.gap_depth_mm);
    ValidateNotNegative(field + "offset_mm", j.offset_mm);
    ValidateClockHours(field + "offset_clock_h", j.offset_clock_h);
    ValidateClockHours(field + "deflection_clock_h", j.deflection_clock_h);
    const double max_gap = 0.5 * std::min(sections[i].length_mm, sections[i + 1].length_mm);
    SEWER3D_VALIDATE(j.gap_mm < max_gap, field + "gap_mm",
                     "must be less than half the shorter neighbouring section ("
                         << max_gap << "), got " << j.gap_mm);
    SEWER3D_VALIDATE(j.gap_depth_mm < 0.2 * sections[i].diameter_mm, field + "gap_depth_mm",
                     "must be less than 20 % of the section's diameter ("
                         << 0.2 * sections[i].diameter_mm << "), got " << j.gap_depth_mm);
    SEWER3D_VALIDATE(j.offset_mm < 0.2 * sections[i].diameter_mm, field + "offset_mm",
                     "must be less than 20 % of the section's diameter ("
                         << 0.2 * sections[i].diameter_mm << "), got " << j.offset_mm);
    SEWER3D_VALIDATE(std::abs(j.deflection_deg) <= 10.0, field + "deflection_deg",
                     "must be within ±10, got " << j.deflection_deg);
  }
  CheckUniqueIds();
  SEWER3D_VALIDATE(features.size() <= PipeFeature::kMaxCount, "features",
                   "at most " << PipeFeature::kMaxCount << " features, got " << features.size());
  double smallest = sections.front().diameter_mm;
  for (const PipeSection& s : sections) smallest = std::min(smallest, s.diameter_mm);
  for (size_t i = 0; i < features.size(); ++i) {
    const PipeFeature& f = features[i];
    const std::string field = "features[" + std::to_string(i) + "].";
    using T = PipeFeature::Type;
    SEWER3D_VALIDATE(f.type == T::kConnection || f.type == T::kSpalling || f.type == T::kCrack ||
                         f.type == T::kDeposit || f.type == T::kWet,
                     field + "type",
                     "must be connection, spalling, crack, deposit or wet, got "
                         << PipeFeatureTypeName(f.type)
                         << " (bump, pit and joint belong to pipe-wall scenes; a pipe's joints "
                            "go in \"joints\")");
    CheckWithin(field, [&] { f.CheckInPipe(smallest); });
    ValidateClockHours(field + "clock_h", f.clock_h);
    // Sediment settles where gravity takes it: the invert (clock 6), give or take a pipe
    // laid with a cross fall or a bed pushed aside by the flow.
    SEWER3D_VALIDATE(
        f.type != T::kDeposit || std::abs(std::remainder(f.clock_h - 6.0, 12.0)) <= 1.5,
        field + "clock_h",
        "a deposit settles at the invert: must be within 6 ± 1.5 h, got " << f.clock_h);
    SEWER3D_VALIDATE(f.station_mm >= 0.0 && f.station_mm <= LengthMm(), field + "station_mm",
                     "must be on the pipe, 0.." << LengthMm() << ", got " << f.station_mm);
    CheckFeatureOnPipe(f, field, smallest);
    for (const PipeSection& s : sections) {
      SEWER3D_VALIDATE(f.intrusion_mm < 0.4 * s.diameter_mm, field + "intrusion_mm",
                       "must be less than 40 % of every section's diameter (Ø"
                           << s.diameter_mm << ": " << 0.4 * s.diameter_mm << "), got "
                           << f.intrusion_mm);
      SEWER3D_VALIDATE(f.height_mm < 0.5 * s.diameter_mm, field + "height_mm",
                       "must be less than half of every section's diameter (Ø"
                           << s.diameter_mm << ": " << 0.5 * s.diameter_mm << "), got "
                           << f.height_mm);
    }
  }
  CheckFeaturesApart(0.5 * smallest);
}

void PipeWorld::CheckFeatureOnPipe(const PipeFeature& f, const std::string& field,
                                   double smallest) const {
  // Where the feature reaches along the pipe: the whole of it must be on the pipe, or the
  // truth would list more (a longer crack, a larger hole) than the pipe shows.
  double from = f.station_mm, to = f.station_mm;
  switch (f.type) {
    case PipeFeature::Type::kConnection:
      from -= 0.5 * f.diameter_mm + f.wall_mm;
      to += 0.5 * f.diameter_mm + f.wall_mm;
      break;
    case PipeFeature::Type::kDeposit:
      to += f.length_mm;
      break;
    case PipeFeature::Type::kCrack: {
      const double along = 0.5 * f.length_mm * std::abs(std::cos(DegToRad(f.angle_deg))) +
                           0.5 * f.width_mm * std::abs(std::sin(DegToRad(f.angle_deg)));
      from -= along;
      to += along;
      break;
    }
    case PipeFeature::Type::kSpalling:
    case PipeFeature::Type::kWet:
      from -= 0.5 * f.length_mm;
      to += 0.5 * f.length_mm;
      break;
    default:
      break;
  }
  // Around the pipe: no wider than its circumference (the smallest section's).
  const double circumference = std::numbers::pi * smallest;
  double around = 0.0;
  if (f.type == PipeFeature::Type::kCrack) {
    around = f.length_mm * std::abs(std::sin(DegToRad(f.angle_deg))) +
             f.width_mm * std::abs(std::cos(DegToRad(f.angle_deg)));
  } else if (f.type == PipeFeature::Type::kSpalling || f.type == PipeFeature::Type::kWet) {
    around = f.width_mm;
  }
  SEWER3D_VALIDATE(around <= circumference,
                   field + (f.type == PipeFeature::Type::kCrack ? "length_mm" : "width_mm"),
                   "'" << f.id << "' spans " << around << " mm around the pipe, more than its "
                       << circumference << " mm circumference (Ø" << smallest << ")");
  SEWER3D_VALIDATE(from >= 0.0 && to <= LengthMm(), field + "station_mm",
                   "'" << f.id << "' reaches from station " << from << " to " << to
                       << " mm, beyond the pipe (0.." << LengthMm()
                       << " mm): move it or make it shorter");
}

void PipeWorld::CheckFeaturesApart(double radius_mm) const {
  // Two features of a kind in one place render as one, while the truth lists both: a feature
  // copied without moving it. Two connections cannot share a hole in the wall.
  for (size_t j = 0; j < features.size(); ++j) {
    for (size_t i = 0; i < j; ++i) {
      const PipeFeature &a = features[i], &b = features[j];
      if (a.type != b.type) continue;
      const double turn_h = std::abs(std::remainder(a.clock_h - b.clock_h, 12.0));
      const double along = std::abs(a.station_mm - b.station_mm);
      const double apart = std::hypot(along, radius_mm * turn_h * std::numbers::pi / 6.0);
      const bool same_place = along <= 1.0 && turn_h <= 0.05;
      const bool holes_meet = a.type == PipeFeature::Type::kConnection &&
                              apart < 0.5 * (a.diameter_mm + b.diameter_mm) + a.wall_mm + b.wall_mm;
      SEWER3D_VALIDATE(!same_place && !holes_meet, "features[" + std::to_string(j) + "]",
                       "'" << b.id << "' lies " << apart << " mm from '" << a.id << "' (features["
                           << i << "]) on the wall, "
                           << (holes_meet ? "and two connections cannot share a hole"
                                          : "a feature of the same type in the same place")
                           << ": copied without moving it? change its station_mm or clock_h");
    }
  }
}

void PipeWorld::CheckUniqueIds() const {
  // Truth files and the inspection's evaluation name joints and features by id.
  std::set<std::string> ids;
  for (size_t i = 0; i < joints.size(); ++i) {
    SEWER3D_VALIDATE(ids.insert(joints[i].id).second, "joints[" + std::to_string(i) + "].id",
                     "'" << joints[i].id << "' is used twice");
  }
  for (size_t i = 0; i < features.size(); ++i) {
    SEWER3D_VALIDATE(ids.insert(features[i].id).second, "features[" + std::to_string(i) + "].id",
                     "'" << features[i].id
                         << "' is used twice (ids of joints and features "
                            "must differ)");
  }
}

double PipeWorld::LengthMm() const {
  double l = 0.0;
  for (const auto& s : sections) l += s.length_mm;
  return l;
}

PipeGeometry::PipeGeometry(PipeWorld world) : world_(std::move(world)) {
  world_.Check();
  const size_t n = world_.sections.size();
  start_station_.resize(n);
  section_start_.resize(n);
  double station = 0.0;
  Rigid3d start = Rigid3d::Identity();
  for (size_t i = 0; i < n; ++i) {
    start_station_[i] = station;
    section_start_[i] = start;
    start_inverse_rotation_.push_back(start.Inverse().RotationMatrix());
    start_inverse_translation_.push_back(start.Inverse().translation);
    station += world_.sections[i].length_mm;
    if (i + 1 == n) break;
    const PipeJoint& j = world_.joints[i];
    const Rigid3d end = start * LocalFrame(world_.sections[i], world_.sections[i].length_mm);
    // The next axis moves away from offset_clock, so its wall there is offset_mm inward.
    const Eigen::Vector3d shift = -j.offset_mm * ClockDirection(ClockHoursToRad(j.offset_clock_h));
    const Eigen::Vector3d turn_axis =
        Eigen::Vector3d::UnitZ().cross(ClockDirection(ClockHoursToRad(j.deflection_clock_h)));
    const Eigen::Quaterniond turn(Eigen::AngleAxisd(DegToRad(j.deflection_deg), turn_axis));
    start = end * Rigid3d(turn, shift);
    joint_point_.push_back(0.5 * (end.translation + start.translation));
    joint_normal_.push_back(
        (end.rotation * Eigen::Vector3d::UnitZ() + start.rotation * Eigen::Vector3d::UnitZ())
            .normalized());
  }
}

Rigid3d PipeGeometry::SectionFrame(int section, double local_mm) const {
  return section_start_[section] * LocalFrame(world_.sections[section], local_mm);
}

Rigid3d PipeGeometry::PathFrame(double station_mm, double blend_mm) const {
  const int n = static_cast<int>(start_station_.size());
  const int i = std::max(0, static_cast<int>(std::upper_bound(start_station_.begin(),
                                                              start_station_.end(), station_mm) -
                                             start_station_.begin()) -
                                1);
  Rigid3d here = SectionFrame(i, station_mm - start_station_[i]);
  const double end = start_station_[i] + world_.sections[i].length_mm;
  if (i + 1 < n && station_mm > end - blend_mm) {
    const double w = SmoothStep((station_mm - end) / (2.0 * blend_mm));
    return Blend(here, SectionFrame(i + 1, station_mm - start_station_[i + 1]), w);
  }
  if (i > 0 && station_mm < start_station_[i] + blend_mm) {
    const double w = SmoothStep((start_station_[i] - station_mm) / (2.0 * blend_mm));
    return Blend(here, SectionFrame(i - 1, station_mm - start_station_[i - 1]), w);
  }
  return here;
}

PipeLocation PipeGeometry::Locate(const Eigen::Vector3d& p) const { return LocateAt(p, true); }

namespace {

// The clock angle costs an atan2: computed only where a feature or deformation needs it.
void EnsureClock(PipeLocation& at) {
  if (std::isnan(at.clock_rad)) at.clock_rad = std::atan2(at.radial.x(), -at.radial.y());
}

}  // namespace

PipeLocation PipeGeometry::LocateAt(const Eigen::Vector3d& p, bool with_clock) const {
  // Sections are ordered along the pipe: the point is beyond joints 0 .. k-1 and before k.
  int lo = 0, hi = static_cast<int>(joint_point_.size());
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if ((p - joint_point_[mid]).dot(joint_normal_[mid]) >= 0.0)
      lo = mid + 1;
    else
      hi = mid;
  }
  PipeLocation at;
  at.section = lo;
  const PipeSection& s = world_.sections[lo];
  const Eigen::Vector3d local = start_inverse_rotation_[lo] * p + start_inverse_translation_[lo];
  at.local_mm = LocalArc(s, local);
  at.station_mm = start_station_[lo] + at.local_mm;
  const Eigen::Vector3d q =
      s.bend_radius_mm > 0.0 ? LocalFrame(s, at.local_mm).Inverse() * local : local;
  at.rho_mm = std::sqrt(q.x() * q.x() + q.y() * q.y());
  at.radial = {q.x(), q.y()};
  at.clock_rad = NAN;
  if (with_clock) EnsureClock(at);
  return at;
}

double PipeGeometry::Displacement(PipeLocation at, Material* material) const {
  const PipeSection& s = world_.sections[at.section];
  const double radius = 0.5 * s.diameter_mm;
  double d = 0.0;
  // Open gaps at the joints before and after this section.
  if (at.section > 0) {
    const PipeJoint& j = world_.joints[at.section - 1];
    if (j.gap_depth_mm > 0.0)
      d -= j.gap_depth_mm * (1.0 - SmoothStep((at.local_mm - 0.5 * j.gap_mm) / kFeatureEdgeMm));
  }
  if (at.section + 1 < static_cast<int>(world_.sections.size())) {
    const PipeJoint& j = world_.joints[at.section];
    if (j.gap_depth_mm > 0.0) {
      d -= j.gap_depth_mm *
           (1.0 - SmoothStep((s.length_mm - 0.5 * j.gap_mm - at.local_mm) / kFeatureEdgeMm));
    }
  }
  return AddPipeFeatures(
      d, world_.features, world_.material_seed, radius, at.station_mm,
      [&at] {
        EnsureClock(at);
        return at.clock_rad;
      },
      material);
}

double PipeGeometry::WallRadiusMm(const PipeLocation& at) const {
  const PipeSection& s = world_.sections[at.section];
  double radius = 0.5 * s.diameter_mm;
  if (s.ovality_pct > 0.0) {
    const double ramp = std::min(100.0, 0.25 * s.length_mm);
    const double w = std::min(SmoothStep(at.local_mm / ramp - 0.5),
                              SmoothStep((s.length_mm - at.local_mm) / ramp - 0.5));
    PipeLocation with_clock = at;
    EnsureClock(with_clock);
    radius *= 1.0 - 0.01 * s.ovality_pct * w *
                        std::cos(2.0 * (with_clock.clock_rad - ClockHoursToRad(s.ovality_clock_h)));
  }
  return radius - Displacement(at, nullptr);
}

double PipeGeometry::SignedDistanceMm(const Eigen::Vector3d& p) const {
  const PipeLocation at = LocateAt(p, false);
  return at.rho_mm - WallRadiusMm(at);
}

std::optional<SurfaceHit> PipeGeometry::Intersect(const Eigen::Vector3d& origin,
                                                  const Eigen::Vector3d& direction) const {
  const double scale = direction.norm();
  if (!(scale > 0.0)) return std::nullopt;
  const Eigen::Vector3d d = direction / scale;
  const PipeLocation start = Locate(origin);
  if (start.rho_mm >= WallRadiusMm(start)) return std::nullopt;  // origin outside the wall
  // First guess: the nominal cylinder of the section around the origin.
  const Rigid3d frame = SectionFrame(start.section, start.local_mm);
  const Eigen::Vector3d o_l = frame.Inverse() * origin, d_l = frame.rotation.conjugate() * d;
  const double radius = 0.5 * world_.sections[start.section].diameter_mm;
  const double A = d_l.head<2>().squaredNorm(), B = 2.0 * o_l.head<2>().dot(d_l.head<2>());
  const double C = o_l.head<2>().squaredNorm() - radius * radius;
  if (A < 1e-12) return std::nullopt;  // along the axis
  const double t0 = (-B + std::sqrt(std::max(0.0, B * B - 4.0 * A * C))) / (2.0 * A);
  auto g = [&](double t) { return SignedDistanceMm(origin + t * d); };
  // Bracket the wall from the guess with steps sized by the guess's error (the nominal
  // cylinder's slope dρ/dt converts it to t), doubling until the sign changes; then refine.
  const double slope =
      std::max(0.05, (o_l.head<2>() + t0 * d_l.head<2>()).dot(d_l.head<2>()) / radius);
  double a = t0, b = t0, ga = g(t0), gb = ga;
  const double first_step = std::max(0.02, 1.5 * std::abs(ga) / slope);
  if (ga > 0.0) {
    for (double step = first_step; ga > 0.0; step *= 2.0) {
      b = a, gb = ga;
      if (a <= 1e-6) return std::nullopt;
      a = std::max(1e-6, t0 - step);
      ga = g(a);
    }
  } else {
    for (double step = first_step; gb <= 0.0; step *= 2.0) {
      if (step > 2048.0) return std::nullopt;
      a = b, ga = gb;
      b = t0 + step;
      gb = g(b);
    }
  }
  const double t = IllinoisRoot(g, a, b, ga, gb, 1e-6);
  SurfaceHit hit;
  hit.t = t / scale;
  hit.point = origin + t * d;
  const PipeLocation at = Locate(hit.point);
  hit.material = world_.sections[at.section].material;
  Displacement(at, &hit.material);
  // Normal from the gradient of the signed distance (forward differences).
  constexpr double h = 1e-3;
  const double g0 = at.rho_mm - WallRadiusMm(at);
  Eigen::Vector3d gradient;
  for (int k = 0; k < 3; ++k)
    gradient[k] = (SignedDistanceMm(hit.point + h * Eigen::Vector3d::Unit(k)) - g0) / h;
  Eigen::Vector3d normal = -gradient.normalized();
  if (!normal.allFinite()) normal = -d;
  hit.normal = normal.dot(d) < 0.0 ? normal : -normal;
  const double radius_at = 0.5 * world_.sections[at.section].diameter_mm;
  hit.surface_mm = {at.clock_rad * radius_at, at.station_mm};
  hit.film = WetCover(world_.features, world_.material_seed, radius_at, at.station_mm,
                      [&at] { return at.clock_rad; });
  return hit;
}

}  // namespace sewer3d
