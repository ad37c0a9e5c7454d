#include "sewer3d/sim/rig.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/pipe_world.hpp"

namespace sewer3d {

void RigOptions::Check() const {
  SEWER3D_VALIDATE(modules >= 1 && modules <= 12, "modules", "must be 1..12, got " << modules);
  ValidateNotNegative("stagger_mm", stagger_mm);
  ValidateClockHours("first_clock_h", first_clock_h);
  ValidatePositive("carrier_diameter_mm", carrier_diameter_mm);
  ValidatePositive("carrier_length_mm", carrier_length_mm);
  // The modules sit along the carrier: their span must fit in it (the baseline is checked
  // with the module, in MakeRig).
  const double span_mm = (modules - 1) * stagger_mm;
  SEWER3D_VALIDATE(span_mm <= carrier_length_mm, "stagger_mm",
                   stagger_mm << " mm puts the " << modules << " modules over " << span_mm
                              << " mm, more than the carrier's length (" << carrier_length_mm
                              << " mm)");
}

Rig MakeRig(const ModuleDescription& module, const RigOptions& o) {
  o.Check();
  module.Check();
  Rig rig;
  rig.carrier_diameter_mm = o.carrier_diameter_mm;
  rig.carrier_length_mm = o.carrier_length_mm;
  const Eigen::Vector3d projector_in_camera = module.projector_from_camera.Inverse().translation;
  for (int k = 0; k < o.modules; ++k) {
    RigModule m;
    m.name = "m";
    m.name += std::to_string(k);  // not "m" + …: GCC 12 warns falsely (-Wrestrict) there
    m.clock_h = std::fmod(o.first_clock_h + 12.0 * k / o.modules, 12.0);
    if (m.clock_h <= 1e-9) m.clock_h += 12.0;  // clock positions run 0+ .. 12
    m.module = module;
    m.module.source_json.clear();
    const Eigen::Vector3d z = ClockDirection(ClockHoursToRad(m.clock_h)),
                          y = Eigen::Vector3d::UnitZ();
    Eigen::Matrix3d r;
    r.col(0) = y.cross(z);
    r.col(1) = y;
    r.col(2) = z;
    // Centre each camera-projector pair on its stagger position along the axis.
    const double pair_centre = (k - 0.5 * (o.modules - 1)) * o.stagger_mm;
    const double camera_z = pair_centre - 0.5 * projector_in_camera.y();
    m.carrier_from_camera = Rigid3d(r, Eigen::Vector3d(0.0, 0.0, camera_z));
    rig.modules.push_back(m);
  }
  // In the options' terms: the stagger (with the module's baseline) sets what fits.
  try {
    rig.Check();
  } catch (const InvalidValue& e) {
    std::ostringstream problem;
    problem << "the " << o.modules << " modules at " << o.stagger_mm << " mm do not fit in the "
            << o.carrier_length_mm << " mm carrier (" << e.what() << ")";
    throw InvalidValue("stagger_mm", problem.str());
  }
  return rig;
}

WallCoverage ModuleCoverage(const Rig& rig, int index, double diameter,
                            const Eigen::Vector2d& offset, bool lit, int step_px) {
  PipeWorld world;
  world.sections.push_back({.length_mm = 4.0 * rig.carrier_length_mm, .diameter_mm = diameter});
  const PipeGeometry pipe(world);
  const double centre = 2.0 * rig.carrier_length_mm;
  const RigModule& m = rig.modules[index];
  const Rigid3d world_from_carrier(Eigen::Quaterniond::Identity(),
                                   Eigen::Vector3d(offset.x(), offset.y(), centre));
  const Rigid3d world_from_camera = world_from_carrier * m.carrier_from_camera;
  const CameraModel camera(m.module.camera), projector(m.module.projector);
  const double nominal = ClockHoursToRad(m.clock_h);
  WallCoverage c;
  c.clock_from_deg = c.station_from_mm = 1e9;
  c.clock_to_deg = c.station_to_mm = -1e9;
  const int w = m.module.camera.width, h = m.module.camera.height;
  for (int v = 0; v < h + step_px; v += step_px) {
    for (int u = 0; u < w + step_px; u += step_px) {
      const auto xy = camera.Unproject({std::min(u, w - 1), std::min(v, h - 1)});
      if (!xy) continue;
      const auto hit =
          pipe.Intersect(world_from_camera.translation,
                         world_from_camera.rotation * Eigen::Vector3d(xy->x(), xy->y(), 1.0));
      if (!hit) continue;
      if (lit) {
        const Eigen::Vector3d p =
            m.module.projector_from_camera * (world_from_camera.Inverse() * hit->point);
        const auto uv = projector.Project(p);
        if (!uv || uv->x() < -0.5 || uv->y() < -0.5 || uv->x() > m.module.projector.width - 0.5 ||
            uv->y() > m.module.projector.height - 0.5) {
          continue;
        }
      }
      const PipeLocation at = pipe.Locate(hit->point);
      const double clock = RadToDeg(nominal + std::remainder(at.clock_rad - nominal, kTwoPi));
      c.any = true;
      c.clock_from_deg = std::min(c.clock_from_deg, clock);
      c.clock_to_deg = std::max(c.clock_to_deg, clock);
      c.station_from_mm = std::min(c.station_from_mm, at.station_mm - centre);
      c.station_to_mm = std::max(c.station_to_mm, at.station_mm - centre);
    }
  }
  return c;
}

std::vector<NeighbourOverlap> NeighbourOverlaps(const Rig& rig, double diameter,
                                                const Eigen::Vector2d& offset, bool lit,
                                                int step_px) {
  const int n = static_cast<int>(rig.modules.size());
  std::vector<WallCoverage> cover(n);
  for (int k = 0; k < n; ++k) cover[k] = ModuleCoverage(rig, k, diameter, offset, lit, step_px);
  std::vector<NeighbourOverlap> out;
  for (int k = 0; k < n; ++k) {
    const int next = (k + 1) % n;
    NeighbourOverlap o{k, next, -360.0, 0.0};
    if (cover[k].any && cover[next].any) {
      // Bring the next module's interval next to this one's (they differ by about 360°/n).
      const double behind = cover[k].clock_from_deg - cover[next].clock_from_deg;
      const double shift = behind > 0.0 ? 360.0 * std::ceil(behind / 360.0) : 0.0;
      o.overlap_deg = cover[k].clock_to_deg - (cover[next].clock_from_deg + shift);
    }
    o.overlap_mm = DegToRad(o.overlap_deg) * 0.5 * diameter;
    out.push_back(o);
  }
  return out;
}

}  // namespace sewer3d
