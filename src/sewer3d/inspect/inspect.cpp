#include "sewer3d/inspect/inspect.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/inspect/ring_fit.hpp"
#include "sewer3d/inspect/robust_stats.hpp"

namespace sewer3d {
namespace {

Observation JointObservation(const JointMeasure& j, const CoarseMap& map, const JointOptions& opt) {
  Observation o;
  o.code = "BAJ";
  const char letter =
      j.offset_mm >= opt.min_offset_mm ? 'B' : (j.deflection_deg >= 1.0 ? 'C' : 'A');
  o.characterisation = std::string(1, letter);
  o.station_mm = j.station_mm;
  // Where it is most pronounced: the offset's clock, or for a joint that is only deflected
  // (C) the clock its next pipe turns toward (an offset of a few hundredths has no clock).
  o.clock_h = o.clock_from_h = o.clock_to_h =
      ClockRadToHours(letter == 'C' ? j.deflection_clock_rad : j.offset_clock_rad);
  o.at_joint = true;
  // A joint found by its step whose gap no column shows open: the gap is narrower than the
  // depth maps resolve (their lit spots bridge it), not closed; and a gap whose bottom is not
  // seen has no depth. Neither is measured (NaN), never 0.
  const double none = std::numeric_limits<double>::quiet_NaN();
  o.quantities = {{"offset_mm", j.offset_mm, "mm"},
                  {"gap_mm", j.gap_mm > 0.0 ? j.gap_mm : none, "mm"},
                  {"deflection_deg", j.deflection_deg, "deg"},
                  {"deflection_clock_h", ClockRadToHours(j.deflection_clock_rad), "h"},
                  {"gap_depth_mm", j.gap_depth_mm > 0.0 ? j.gap_depth_mm : none, "mm"}};
  const double strength =
      std::max(j.gap_depth_mm / opt.min_gap_depth_mm, j.offset_mm / opt.min_offset_mm);
  o.confidence = j.side_coverage * (1.0 - std::exp(-strength));
  const int side = static_cast<int>(opt.side_length_mm / map.RowMm());
  o.crop.row0 = std::max(0, map.FineRow(j.row_begin - side));
  o.crop.rows = std::min(map.fine.rows, map.FineRow(j.row_end + side)) - o.crop.row0;
  // A quarter of the turn around where the offset is largest (the whole ring is too long a
  // strip to look at).
  const int quarter = map.fine.cols / 4;
  const int at =
      static_cast<int>(std::lround(j.offset_clock_rad / (2.0 * std::numbers::pi) * map.fine.cols));
  o.crop.col0 = ((at - quarter / 2) % map.fine.cols + map.fine.cols) % map.fine.cols;
  o.crop.cols = quarter;
  const std::string gap = j.gap_mm > 0.0 ? fmt::format("gap {:.1f} mm", j.gap_mm)
                                         : std::string("gap not resolved in the maps");
  o.remark = fmt::format("joint: offset {:.1f} mm at {:.1f} h, {}, deflection {:.2f}°", j.offset_mm,
                         o.clock_h, gap, j.deflection_deg);
  return o;
}

/// The stretches between the joints' bands (each gap and band_mm either side of it).
std::vector<RowRange> Sections(const std::vector<JointMeasure>& joints, const CoarseMap& map,
                               double band_mm) {
  const int rows = map.displacement_mm.rows;
  std::vector<RowRange> out;
  int begin = 0;
  for (const JointMeasure& j : joints) {
    const double half = 0.5 * j.gap_mm + band_mm, s0 = map.fine.station0_mm;
    const int first =
        std::max(0, static_cast<int>(std::floor((j.station_mm - half - s0) / map.RowMm())));
    if (first > begin) out.push_back({begin, first});
    begin = std::max(begin, static_cast<int>(std::ceil((j.station_mm + half - s0) / map.RowMm())));
  }
  if (rows > begin) out.push_back({begin, rows});
  return out;
}

/// The stations a section's pipe runs over: from the joint before it to the joint after it
/// (the section's rows leave out the joints' bands), or to the section's own end where no
/// joint bounds it.
std::pair<double, double> PipeExtent(const std::vector<JointMeasure>& joints, const CoarseMap& map,
                                     const RowRange& s) {
  const double s0 = map.fine.station0_mm;
  double from = s0 + s.begin * map.RowMm(), to = s0 + s.end * map.RowMm();
  const double begin = from, end = to;
  double before = -std::numeric_limits<double>::infinity();
  double after = std::numeric_limits<double>::infinity();
  for (const JointMeasure& j : joints) {
    if (j.station_mm <= begin) before = std::max(before, j.station_mm);
    if (j.station_mm >= end) after = std::min(after, j.station_mm);
  }
  if (s.begin > 0 && std::isfinite(before)) from = before;
  if (s.end < map.displacement_mm.rows && std::isfinite(after)) to = after;
  return {from, to};
}

/// BAA for a section whose median smooth wall has a diameter reduced by ≥ the threshold,
/// reported over the pipe's extent (PipeExtent): a pipe deforms as a whole.
bool Deformation(const CoarseMap& map, const std::vector<RingFit>& fits, const RowRange& s,
                 std::pair<double, double> extent, double radius, double dn, double min_pct,
                 Observation& o) {
  std::vector<double> k[5];
  for (int r = s.begin; r < s.end; ++r) {
    if (!fits[r].valid) continue;
    for (int j = 0; j < 5; ++j) k[j].push_back(fits[r].k(j));
  }
  if (k[0].size() < 10) return false;
  double med[5];
  for (int j = 0; j < 5; ++j) med[j] = Median(k[j]);
  // Diameter along θ: 2 (R + a0 + c2 cos 2θ + s2 sin 2θ); the axis terms cancel.
  const double amp = std::hypot(med[3], med[4]), phase = std::atan2(med[4], med[3]);
  auto diameter = [&](double th) {
    return 2.0 * (radius + med[0] + med[3] * std::cos(2 * th) + med[4] * std::sin(2 * th));
  };
  const double theta_min = std::fmod(0.5 * (phase + std::numbers::pi), std::numbers::pi);
  const double reduction = 100.0 * (dn - 2.0 * (radius + med[0] - amp)) / dn;
  if (reduction < min_pct) return false;
  o.code = "BAA";
  const double vertical = std::abs(std::cos(theta_min));
  o.characterisation = vertical >= std::sqrt(0.5) ? "A" : "B";
  o.station_mm = extent.first;
  o.length_mm = extent.second - extent.first;
  o.clock_h = ClockRadToHours(theta_min);
  o.clock_from_h = o.clock_to_h = o.clock_h;
  o.quantities = {
      {"deformation_pct", reduction, "%"},
      {"vertical_change_pct", 100.0 * (diameter(0.0) - dn) / dn, "%"},
      {"horizontal_change_pct", 100.0 * (diameter(0.5 * std::numbers::pi) - dn) / dn, "%"},
      {"ovality_astm_pct", 100.0 * 2.0 * amp / (2.0 * (radius + med[0])), "%"}};
  o.confidence = std::min(1.0, static_cast<double>(k[0].size()) / (s.end - s.begin)) *
                 (1.0 - std::exp(-reduction / min_pct));
  o.crop = {map.FineRow(s.begin), map.FineRow(s.end - s.begin), 0, map.fine.cols};
  o.remark = fmt::format("deformation {:.1f} % toward {:.1f} h", reduction, o.clock_h);
  return true;
}

void InspectedRange(const CoarseMap& map, const std::vector<RingCoefficients>& rings,
                    InspectionReport& rep) {
  int first = -1, last = -1, count = 0;
  for (int r = 0; r < static_cast<int>(rings.size()); ++r) {
    if (!std::isfinite(rings[r](0))) continue;
    if (first < 0) first = r;
    last = r;
    ++count;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  rep.inspected_from_mm = first < 0 ? nan : map.RowStationMm(first);
  rep.inspected_to_mm = last < 0 ? nan : map.RowStationMm(last);
  rep.inspected_share = rings.empty() ? 0.0 : static_cast<double>(count) / rings.size();
}

/// Cracks in the texture (texture_cracks.hpp) outside the observations found so far and the
/// joints' bands, whose edges are dark lines too.
void AddTextureCracks(const CoarseMap& map, const std::vector<JointMeasure>& joints, double radius,
                      const InspectOptions& options, std::vector<Observation>& observations) {
  std::vector<MapCrop> excluded;
  for (const Observation& o : observations) excluded.push_back(o.crop);
  for (const JointMeasure& j : joints) {
    const double half = 0.5 * j.gap_mm + options.joint_band_mm;
    const int first =
        std::max(0, static_cast<int>(std::floor((j.station_mm - half - map.fine.station0_mm) /
                                                map.fine.resolution_mm)));
    const int last = std::min(
        map.fine.rows, static_cast<int>(std::ceil((j.station_mm + half - map.fine.station0_mm) /
                                                  map.fine.resolution_mm)));
    if (last > first) excluded.push_back({first, last - first, 0, map.fine.cols});
  }
  for (Observation& o : FindTextureCracks(map, radius, excluded, options.cracks))
    observations.push_back(std::move(o));
}

}  // namespace

void InspectOptions::Check() const {
  ValidatePositive("cell_mm", cell_mm);
  ValidatePositive("max_map_cell_mm", max_map_cell_mm);
  SEWER3D_VALIDATE(cell_mm <= max_map_cell_mm, "cell_mm",
                   "must be ≤ max_map_cell_mm (" << max_map_cell_mm << " mm), got " << cell_mm);
  ValidateNotNegative("nominal_diameter_mm", nominal_diameter_mm);
  SEWER3D_VALIDATE(min_ring_coverage > 0.0 && min_ring_coverage <= 1.0, "min_ring_coverage",
                   "must be in (0, 1], got " << min_ring_coverage);
  ValidatePositive("smoothing_mm", smoothing_mm);
  ValidatePositive("min_deformation_pct", min_deformation_pct);
  ValidateNotNegative("joint_flag_mm", joint_flag_mm);
  ValidateNotNegative("joint_band_mm", joint_band_mm);
  CheckWithin("joints.", [&] { joints.Check(); });
  CheckWithin("defects.", [&] { defects.Check(); });
  CheckWithin("cracks.", [&] { cracks.Check(); });
}

void CheckNominalDiameter(const InspectOptions& options, double radius_mm) {
  const double dn =
      options.nominal_diameter_mm > 0.0 ? options.nominal_diameter_mm : 2.0 * radius_mm;
  SEWER3D_VALIDATE(
      std::abs(dn - 2.0 * radius_mm) <= 0.25 * 2.0 * radius_mm, "nominal_diameter_mm",
      "must be within 25 % of the model's diameter (" << 2.0 * radius_mm << " mm), got " << dn);
}

Inspection Inspect(const CoarseMap& map, const Centreline& centreline,
                   const InspectOptions& options) {
  options.Check();
  CheckNominalDiameter(options, centreline.radius_mm);
  const double radius = centreline.radius_mm;
  const double dn = options.nominal_diameter_mm > 0.0 ? options.nominal_diameter_mm : 2.0 * radius;
  SEWER3D_VALIDATE(map.RowMm() <= options.max_map_cell_mm * (1.0 + 1e-9), "map",
                   "cells of " << map.RowMm() << " mm are coarser than max_map_cell_mm ("
                               << options.max_map_cell_mm << " mm)");
  Inspection out;
  InspectionReport& rep = out.report;
  rep.coarse_rows = map.displacement_mm.rows;
  rep.coarse_cols = map.displacement_mm.cols;
  rep.cell_mm = map.RowMm();
  const std::vector<RingFit> fits = FitRings(map, options.min_ring_coverage);
  for (const RingFit& f : fits) rep.valid_rings += f.valid ? 1 : 0;
  const std::vector<JointMeasure> joints = FindJoints(map, fits, centreline, options.joints);
  const std::vector<RowRange> sections = Sections(joints, map, options.joint_band_mm);
  rep.sections = static_cast<int>(sections.size());
  const int half = std::max(1, static_cast<int>(options.smoothing_mm / map.RowMm()));
  const std::vector<RingCoefficients> rings = SmoothRings(fits, sections, half);
  InspectedRange(map, rings, rep);
  const cv::Mat1f residual = RingResidual(map, rings);
  rep.residual_sigma_mm = RobustSigma(residual);
  out.observations = FindDefects(map, residual, radius, dn, rep.residual_sigma_mm, options.defects);
  AddTextureCracks(map, joints, radius, options, out.observations);
  for (Observation& o : out.observations) {
    const double begin = o.station_mm - (IsContinuous(o) ? 0.0 : 0.5 * o.length_mm);
    for (const JointMeasure& j : joints) {
      const double gap = std::max(begin - j.station_mm, j.station_mm - (begin + o.length_mm));
      o.at_joint = o.at_joint || gap <= options.joint_flag_mm;
    }
  }
  for (const JointMeasure& j : joints) {
    Observation o = JointObservation(j, map, options.joints);
    if (o.confidence > 0.0) out.observations.push_back(std::move(o));
  }
  for (const RowRange& s : sections) {
    Observation o;
    if (Deformation(map, fits, s, PipeExtent(joints, map, s), radius, dn,
                    options.min_deformation_pct, o))
      out.observations.push_back(o);
  }
  std::stable_sort(
      out.observations.begin(), out.observations.end(),
      [](const Observation& a, const Observation& b) { return a.station_mm < b.station_mm; });
  for (std::size_t i = 0; i < out.observations.size(); ++i)
    out.observations[i].id = fmt::format("O{}", i + 1);
  return out;
}

}  // namespace sewer3d
