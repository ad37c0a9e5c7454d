#include "sewer3d/sim/pipe_feature.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

// How far a wet patch's film reaches from its centre along and around the pipe: its ragged
// margin moves the rounded rectangle's edge out by kWetRaggedMm at the shorter side, scaled
// with the side.
Eigen::Vector2d WetReachMm(const PipeFeature& f) {
  const double shorter = 0.5 * std::min(f.length_mm, f.width_mm);
  return 0.5 * Eigen::Vector2d(f.length_mm, f.width_mm) * (1.0 + kWetRaggedMm / shorter);
}

}  // namespace

const char* PipeFeatureTypeName(PipeFeature::Type type) {
  switch (type) {
    case PipeFeature::Type::kConnection:
      return "connection";
    case PipeFeature::Type::kSpalling:
      return "spalling";
    case PipeFeature::Type::kCrack:
      return "crack";
    case PipeFeature::Type::kDeposit:
      return "deposit";
    case PipeFeature::Type::kBump:
      return "bump";
    case PipeFeature::Type::kPit:
      return "pit";
    case PipeFeature::Type::kJointStep:
      return "joint";
    case PipeFeature::Type::kWet:
      return "wet";
  }
  return "connection";
}

std::optional<PipeFeature::Type> PipeFeatureTypeFromName(const std::string& name) {
  using T = PipeFeature::Type;
  for (const T t : {T::kConnection, T::kSpalling, T::kCrack, T::kDeposit, T::kBump, T::kPit,
                    T::kJointStep, T::kWet}) {
    if (name == PipeFeatureTypeName(t)) return t;
  }
  return std::nullopt;
}

void PipeFeature::Check() const {
  // A pipe's features sit at 0..12 h (PipeWorld checks that); a pipe-wall scene counts from
  // the view direction, either way round.
  SEWER3D_VALIDATE(std::abs(clock_h) <= 12.0, "clock_h", "must be within ±12 h, got " << clock_h);
  ValidateNotNegative("gap_mm", gap_mm);
  ValidateNotNegative("length_mm", length_mm);
  ValidateNotNegative("width_mm", width_mm);
  switch (type) {
    case Type::kConnection:
      ValidatePositive("diameter_mm", diameter_mm);
      ValidateNotNegative("wall_mm", wall_mm);
      ValidateNotNegative("intrusion_mm", intrusion_mm);
      break;
    case Type::kSpalling:
    case Type::kCrack:
      ValidatePositive("length_mm", length_mm);
      ValidatePositive("width_mm", width_mm);
      ValidatePositive("depth_mm", depth_mm);
      // A crack is long and narrow: wider than long, or than 50 mm, it is a missing piece.
      SEWER3D_VALIDATE(type != Type::kCrack || (width_mm < length_mm && width_mm <= 50.0),
                       "width_mm",
                       "a crack must be narrower than its length ("
                           << length_mm << " mm) and at most 50 mm wide, got " << width_mm
                           << " (a wide missing piece is spalling)");
      break;
    case Type::kDeposit:
      ValidatePositive("length_mm", length_mm);
      ValidatePositive("height_mm", height_mm);
      break;
    case Type::kBump:
    case Type::kPit:
      ValidatePositive("radius_mm", radius_mm);
      break;
    case Type::kWet:
      ValidatePositive("length_mm", length_mm);
      ValidatePositive("width_mm", width_mm);
      break;
    case Type::kJointStep:
      break;
  }
}

void PipeFeature::CheckInPipe(double d) const {
  Check();
  const auto below = [&](const char* field, double value, double limit, const char* what) {
    SEWER3D_VALIDATE(value < limit, field,
                     "must be less than " << what << " of the pipe's diameter (Ø" << d << ": "
                                          << limit << "), got " << value);
  };
  below("depth_mm", depth_mm, 0.2 * d, "a fifth");
  if (type != Type::kConnection) below("height_mm", height_mm, 0.5 * d, "half");
  if (type == Type::kBump || type == Type::kPit) below("radius_mm", radius_mm, d, "the whole");
  if (type == Type::kConnection) below("diameter_mm", diameter_mm, d, "the whole");
  if (type == Type::kJointStep) {
    below("offset_mm", std::abs(offset_mm), 0.2 * d, "a fifth");
    below("gap_mm", gap_mm, d, "the whole");
  }
}

double PipeFeatureReachMm(const PipeFeature& f) {
  switch (f.type) {
    case PipeFeature::Type::kConnection:
      return 0.5 * f.diameter_mm + f.wall_mm + kFeatureEdgeMm;
    case PipeFeature::Type::kDeposit:
      return f.length_mm;
    case PipeFeature::Type::kSpalling:
    case PipeFeature::Type::kCrack:
      return 0.5 * f.length_mm + f.width_mm + kFeatureEdgeMm;
    case PipeFeature::Type::kWet:
      return WetReachMm(f).x();
    case PipeFeature::Type::kPit:
      return f.radius_mm;
    case PipeFeature::Type::kBump:
      return kBumpReachSigmas * f.radius_mm;
    case PipeFeature::Type::kJointStep:
      break;
  }
  return std::numeric_limits<double>::infinity();
}

double PipeFeatureDisplacementMm(const PipeFeature& f, double ds, double dclock, double radius,
                                 std::uint64_t noise_seed, std::optional<Material>* own_material) {
  const double arc = dclock * radius;
  switch (f.type) {
    case PipeFeature::Type::kConnection: {
      // The lateral's wall end protrudes around its bore, open 60 mm deep or to its radius.
      const double r_in = 0.5 * f.diameter_mm, r_out = r_in + f.wall_mm;
      if (std::abs(ds) > r_out + kFeatureEdgeMm || std::abs(arc) > r_out + kFeatureEdgeMm)
        return 0.0;
      const double r = std::sqrt(ds * ds + arc * arc);
      const double bore = std::min(60.0, r_in);
      if (own_material) *own_material = Material::kVitrifiedClay;
      return f.intrusion_mm * (1.0 - SmoothStep((r - r_out) / kFeatureEdgeMm)) -
             (bore + f.intrusion_mm) * (1.0 - SmoothStep((r - r_in) / kFeatureEdgeMm));
    }
    case PipeFeature::Type::kSpalling: {
      if (std::abs(ds) > 0.5 * f.length_mm + kFeatureEdgeMm ||
          std::abs(arc) > 0.5 * f.width_mm + kFeatureEdgeMm)
        return 0.0;
      // Rounded rectangle (superellipse) with a rough bottom.
      const double u = 2.0 * ds / f.length_mm, v = 2.0 * arc / f.width_mm;
      const double q = std::pow(std::pow(u, 4) + std::pow(v, 4), 0.25);
      const double edge = (q - 1.0) * 0.5 * std::min(f.length_mm, f.width_mm) / kFeatureEdgeMm;
      const double rough = SmoothNoise(noise_seed + 17, ds / 4.0, arc / 4.0, 3);
      return -f.depth_mm * (0.6 + 0.8 * rough) * (1.0 - SmoothStep(edge));
    }
    case PipeFeature::Type::kCrack: {
      // V-shaped groove along angle_deg on the unrolled wall.
      const double reach = 0.5 * f.length_mm + f.width_mm;
      if (std::abs(ds) > reach && std::abs(arc) > reach) return 0.0;
      const double ca = std::cos(DegToRad(f.angle_deg)), sa = std::sin(DegToRad(f.angle_deg));
      const double along = ds * ca + arc * sa, across = -ds * sa + arc * ca;
      if (std::abs(along) > 0.5 * f.length_mm) return 0.0;
      const double q = std::abs(across) / (0.5 * f.width_mm);
      return q < 1.0 ? -f.depth_mm * (1.0 - q) : 0.0;
    }
    case PipeFeature::Type::kDeposit: {
      // A flat bed at the invert, ramped in over ≤ 30 mm at its ends, with a gritty top.
      if (ds < 0.0 || ds > f.length_mm) return 0.0;
      const double ramp = std::min(30.0, 0.25 * f.length_mm);
      const double h = f.height_mm * std::min(SmoothStep(ds / ramp - 0.5),
                                              SmoothStep((f.length_mm - ds) / ramp - 0.5));
      const double c = std::cos(dclock);
      if (c <= 0.0) return 0.0;
      const double grit = 0.3 * (SmoothNoise(noise_seed + 29, ds / 3.0, arc / 3.0, 2) - 0.5);
      if (own_material) *own_material = Material::kSediment;
      return std::max(0.0, radius - (radius - h - grit) / c);
    }
    case PipeFeature::Type::kBump:
      if (std::abs(arc) > kBumpReachSigmas * f.radius_mm) return 0.0;
      return f.height_mm * std::exp(-0.5 * (ds * ds + arc * arc) / (f.radius_mm * f.radius_mm));
    case PipeFeature::Type::kPit: {
      const double q = (ds * ds + arc * arc) / (f.radius_mm * f.radius_mm);
      return q < 1.0 ? -f.depth_mm * (1.0 - q) : 0.0;
    }
    case PipeFeature::Type::kJointStep: {
      // The next section (beyond the gap) displaced laterally toward clock_h; an open gap.
      double d = 0.0;
      if (ds > 0.5 * f.gap_mm) d += f.offset_mm * std::cos(dclock);
      if (std::abs(ds) <= 0.5 * f.gap_mm) d -= f.depth_mm;
      return d;
    }
    case PipeFeature::Type::kWet:
      return 0.0;  // a film has no thickness that counts here
  }
  return 0.0;
}

double PipeFeatureWetCover(const PipeFeature& f, double ds, double dclock, double radius,
                           std::uint64_t noise_seed) {
  if (f.type != PipeFeature::Type::kWet) return 0.0;
  const double arc = dclock * radius;
  const Eigen::Vector2d reach = WetReachMm(f);
  if (std::abs(ds) >= reach.x() || std::abs(arc) >= reach.y()) return 0.0;
  // Distance outside the rounded rectangle (superellipse, as spalling) in mm at its shorter
  // side, its line moved by up to ±kWetRaggedMm (a seeping patch's margin is ragged); the
  // film thins out over the last 2 mm inside it.
  const double half_l = 0.5 * f.length_mm, half_w = 0.5 * f.width_mm;
  const double u = ds / half_l, v = arc / half_w;
  const double q = std::pow(std::pow(u, 4) + std::pow(v, 4), 0.25);
  const double noise = SmoothNoise(noise_seed + 41, ds / 8.0, arc / 8.0, 2);  // mostly 0.25–0.75
  const double ragged = kWetRaggedMm * std::clamp(4.0 * (noise - 0.5), -1.0, 1.0);
  const double outside = (q - 1.0) * std::min(half_l, half_w) + ragged;
  constexpr double kThinningMm = 2.0;
  return 1.0 - SmoothStep(outside / kThinningMm + 0.5);
}

}  // namespace sewer3d
