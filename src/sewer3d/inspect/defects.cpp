#include "sewer3d/inspect/defects.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/inspect/components.hpp"
#include "sewer3d/inspect/robust_stats.hpp"

namespace sewer3d {
namespace {

constexpr double kTurn = 2.0 * std::numbers::pi;

/// Where coarse cells lie on the wall.
struct Wall {
  const CoarseMap& map;
  double radius_mm;
  [[nodiscard]] int Cols() const { return map.displacement_mm.cols; }
  [[nodiscard]] double RowMm() const { return map.RowMm(); }
  [[nodiscard]] double ColMm() const { return map.ColArcMm(radius_mm); }
  [[nodiscard]] double CellMm2() const { return RowMm() * ColMm(); }
  [[nodiscard]] double Station(double row) const {
    return map.fine.station0_mm + (row + 0.5) * RowMm();
  }
  /// Clock angle of an unwrapped column (may exceed one turn).
  [[nodiscard]] double Clock(double ucol) const {
    const int base = static_cast<int>(std::floor(ucol));
    const int turns = base >= 0 ? base / Cols() : -((-base + Cols() - 1) / Cols());
    return map.ColClockRad(Wrap(base)) + (ucol - base) * map.factor * kTurn / map.fine.cols +
           turns * kTurn;
  }
  [[nodiscard]] int Wrap(int ucol) const { return ((ucol % Cols()) + Cols()) % Cols(); }
};

std::vector<double> SignedValues(const cv::Mat1f& res, const Wall& wall,
                                 const std::vector<cv::Point>& cells, double sign) {
  std::vector<double> v;
  v.reserve(cells.size());
  for (const cv::Point& p : cells) {
    const float x = res(p.y, wall.Wrap(p.x));
    if (std::isfinite(x)) v.push_back(sign * x);
  }
  return v;
}

/// The region's core: its cells at least half as deep (sign +1) or high (−1) as its median.
/// Its outline is the half-depth contour, which blurred edges leave where it was.
std::vector<cv::Point> Core(const Wall& wall, const cv::Mat1f& res,
                            const std::vector<cv::Point>& cells, double sign) {
  const double half = 0.5 * Percentile(SignedValues(res, wall, cells, sign), 0.5);
  std::vector<cv::Point> core;
  for (const cv::Point& p : cells) {
    const float v = res(p.y, wall.Wrap(p.x));
    if (std::isfinite(v) && sign * v >= half) core.push_back(p);
  }
  return core;
}

/// The fields every observation of a region has: place, extent, crop, confidence.
Observation Describe(const Wall& wall, const cv::Mat1f& res, const MapComponent& comp, double sign,
                     double magnitude, double threshold) {
  Observation o;
  cv::Point peak = comp.cells.front();
  for (const cv::Point& p : comp.cells) {
    if (sign * res(p.y, wall.Wrap(p.x)) > sign * res(peak.y, wall.Wrap(peak.x))) peak = p;
  }
  o.station_mm = wall.Station(0.5 * (comp.row_min + comp.row_max));
  o.length_mm = (comp.row_max - comp.row_min + 1) * wall.RowMm();
  o.clock_h = ClockRadToHours(wall.Clock(peak.x));
  o.clock_from_h = ClockRadToHours(wall.Clock(comp.col_min - 0.5));
  o.clock_to_h = ClockRadToHours(wall.Clock(comp.col_max + 0.5));
  const int margin = 5, f = wall.map.factor;
  o.crop.row0 = std::max(0, (comp.row_min - margin) * f);
  o.crop.rows = std::min(wall.map.fine.rows, (comp.row_max + 1 + margin) * f) - o.crop.row0;
  o.crop.col0 =
      ((comp.col_min - margin) * f % wall.map.fine.cols + wall.map.fine.cols) % wall.map.fine.cols;
  o.crop.cols = std::min(wall.map.fine.cols, (comp.col_max - comp.col_min + 1 + 2 * margin) * f);
  // Share of the box's cells that were measured, times how far the signal clears the threshold.
  int measured = 0, total = 0;
  for (int r = comp.row_min; r <= comp.row_max; ++r) {
    for (int c = comp.col_min; c <= comp.col_max; ++c, ++total) {
      measured += std::isfinite(wall.map.displacement_mm(r, wall.Wrap(c))) ? 1 : 0;
    }
  }
  o.confidence = static_cast<double>(measured) / total * (1.0 - std::exp(-magnitude / threshold));
  return o;
}

/// A lateral connection: its bore (outward regions deeper than any surface damage, and those
/// next to them) and the inward regions around it (the lateral's intruding end).
struct ConnectionParts {
  std::vector<cv::Point> bore, ring;
  MapComponent box;  ///< bounding box of all parts (cells unused)
};

bool Near(const MapComponent& a, const MapComponent& b, int margin_rows, int margin_cols) {
  return a.row_min <= b.row_max + margin_rows && b.row_min <= a.row_max + margin_rows &&
         a.col_min <= b.col_max + margin_cols && b.col_min <= a.col_max + margin_cols;
}

Observation Connection(const Wall& wall, const cv::Mat1f& res, const ConnectionParts& parts,
                       double dn, double intrusion_threshold) {
  const std::vector<double> inward = SignedValues(res, wall, parts.ring, -1.0);
  const double intrusion = inward.empty() ? 0.0 : Percentile(inward, 0.9);
  MapComponent all = parts.box;
  all.cells = parts.bore;
  all.cells.insert(all.cells.end(), parts.ring.begin(), parts.ring.end());
  const bool intruding = intrusion >= intrusion_threshold;
  Observation o = Describe(wall, res, all, 1.0, intruding ? intrusion : 1.0, intrusion_threshold);
  const std::vector<cv::Point> core = Core(wall, res, parts.bore, 1.0);
  int row_min = core.front().y, row_max = row_min;
  for (const cv::Point& p : core) {
    row_min = std::min(row_min, p.y);
    row_max = std::max(row_max, p.y);
  }
  // Along the pipe a lateral square to it opens exactly its bore (its core: where the depth map
  // bridges the lateral's end, the bore's depth is smeared over it).
  const double bore = (row_max - row_min + 1) * wall.RowMm();
  o.station_mm = wall.Station(0.5 * (row_min + row_max));
  o.clock_h = ClockRadToHours(wall.Clock(0.5 * (parts.box.col_min + parts.box.col_max)));
  if (intruding) {
    o.code = "BAG";
    o.quantities = {{"intrusion_pct_of_dn", 100.0 * intrusion / dn, "%"},
                    {"intrusion_mm", intrusion, "mm"},
                    {"bore_diameter_mm", bore, "mm"}};
    o.remark = fmt::format("connection Ø{:.0f} at {:.1f} h intruding {:.1f} mm", bore, o.clock_h,
                           intrusion);
  } else {
    o.code = "BCA";
    o.quantities = {{"bore_diameter_mm", bore, "mm"}};
    o.remark = fmt::format("connection Ø{:.0f} at {:.1f} h", bore, o.clock_h);
  }
  return o;
}

Observation Deposit(const Wall& wall, const cv::Mat1f& res, const MapComponent& comp, double dn,
                    double threshold) {
  // Height: the bed's highest point per row (at the invert), median over the middle rows.
  const int rows = comp.row_max - comp.row_min + 1;
  std::vector<double> per_row(rows, 0.0);
  for (const cv::Point& p : comp.cells) {
    const float v = -res(p.y, wall.Wrap(p.x));
    if (std::isfinite(v))
      per_row[p.y - comp.row_min] = std::max<double>(per_row[p.y - comp.row_min], v);
  }
  const int cut = rows / 10;
  const std::vector<double> middle(per_row.begin() + cut, per_row.end() - cut);
  const double h = Percentile(middle, 0.5), r = 0.5 * dn;
  const double theta = 2.0 * std::acos(std::clamp((r - h) / r, -1.0, 1.0));
  Observation o = Describe(wall, res, comp, -1.0, h, threshold);
  o.code = "BBC";
  // Its place is the middle of its width: a flat bed's highest cell lies anywhere on it.
  o.clock_h = ClockRadToHours(wall.Clock(0.5 * (comp.col_min + comp.col_max)));
  // The bed's ramps are steep and often not measured: the deposit goes on along the invert
  // through unmeasured rows next to it (up to 50 mm).
  int first = comp.row_min, last = comp.row_max;
  const int invert = static_cast<int>(std::lround(0.5 * (comp.col_min + comp.col_max)));
  const int reach = static_cast<int>(50.0 / wall.RowMm());
  auto open = [&](int r) {
    return r >= 0 && r < res.rows && !std::isfinite(res(r, wall.Wrap(invert)));
  };
  for (int k = 0; k < reach && open(first - 1); ++k) --first;
  for (int k = 0; k < reach && open(last + 1); ++k) ++last;
  o.station_mm = wall.Station(first - 0.5);
  o.length_mm = (last - first + 1) * wall.RowMm();
  o.quantities = {{"cross_section_loss_pct", 100.0 * (theta - std::sin(theta)) / kTurn, "%"},
                  {"height_mm", h, "mm"}};
  o.remark = fmt::format("settled deposit {:.0f} mm high over {:.2f} m", h, o.length_mm / 1000.0);
  return o;
}

/// Length, width (4 σ across) and direction (deg on the unrolled wall, 0 = along the pipe,
/// in (−90, 90]) of a region from the principal axes of its cells.
struct Shape {
  double length_mm = 0.0;
  double width_mm = 0.0;
  double angle_deg = 0.0;
};

Shape ShapeOf(const Wall& wall, const MapComponent& comp) {
  const CellAxis axis = PrincipalAxis(comp.cells, wall.RowMm(), wall.ColMm());
  const double cell = std::hypot(axis.dir.x() * wall.RowMm(), axis.dir.y() * wall.ColMm());
  return {axis.hi - axis.lo + cell, 4.0 * std::sqrt(axis.across_variance_mm2), axis.AngleDeg()};
}

Observation Surface(const Wall& wall, const cv::Mat1f& res, const MapComponent& comp,
                    const DefectOptions& opt, double threshold) {
  const std::vector<double> depth = SignedValues(res, wall, comp.cells, 1.0);
  double sum = 0.0;
  for (double d : depth) sum += d;
  const double max_depth = Percentile(depth, 0.98);
  Observation o = Describe(wall, res, comp, 1.0, max_depth, threshold);
  // A patch's or a crack's place is its middle: its deepest cell lies anywhere on its floor.
  o.clock_h = ClockRadToHours(wall.Clock(0.5 * (comp.col_min + comp.col_max)));
  const Shape shape = ShapeOf(wall, comp);
  if (shape.length_mm >= opt.crack_elongation * shape.width_mm &&
      shape.width_mm <= opt.crack_max_width_mm) {
    // A V-groove's cross-section is depth · width / 2: the width from the mean cross-section.
    const double section_mm2 = sum * wall.CellMm2() / shape.length_mm;
    o.code = "BAB";
    o.quantities = {{"width_mm", 2.0 * section_mm2 / max_depth, "mm"},
                    {"length_mm", shape.length_mm, "mm"},
                    {"angle_deg", shape.angle_deg, "deg"},
                    {"depth_mm", max_depth, "mm"}};
    o.remark = fmt::format("crack {:.0f} mm long at {:.0f}° to the axis", shape.length_mm,
                           shape.angle_deg);
    return o;
  }
  o.code = "BAF";
  const std::vector<cv::Point> core = Core(wall, res, comp.cells, 1.0);
  std::vector<cv::Point> inner =
      InteriorCells(core, static_cast<int>(std::lround(opt.spall_rim_mm / wall.RowMm())),
                    static_cast<int>(std::lround(opt.spall_rim_mm / wall.ColMm())));
  if (inner.empty()) inner = core;  // too narrow for its rim: all of it
  const std::vector<double> inner_depth = SignedValues(res, wall, inner, 1.0);
  double inner_sum = 0.0;
  for (double d : inner_depth) inner_sum += d;
  const double unmeasured = static_cast<double>(comp.cells.size() - depth.size()) * wall.CellMm2();
  const double area = static_cast<double>(core.size()) * wall.CellMm2() + unmeasured;
  o.quantities = {{"depth_max_mm", max_depth, "mm"},
                  {"area_mm2", area, "mm2"},
                  {"depth_mean_mm", inner_sum / static_cast<double>(inner_depth.size()), "mm"},
                  {"width_mm", (comp.col_max - comp.col_min + 1) * wall.ColMm(), "mm"},
                  {"unmeasured_mm2", unmeasured, "mm2"}};
  o.remark = fmt::format("spalling {:.0f} cm² up to {:.1f} mm deep", area / 100.0, max_depth);
  if (unmeasured > 0.0)
    o.remark += fmt::format(" ({:.0f} cm² of it not measured)", unmeasured / 100.0);
  return o;
}

}  // namespace

namespace {

void Grow(MapComponent& box, const MapComponent& c) {
  box.row_min = std::min(box.row_min, c.row_min);
  box.row_max = std::max(box.row_max, c.row_max);
  box.col_min = std::min(box.col_min, c.col_min);
  box.col_max = std::max(box.col_max, c.col_max);
}

/// `regions` where their boxes come within `margin_rows`, `margin_cols` of each other joined
/// (cells listed in order, boxes grown), until no two are that near.
std::vector<MapComponent> MergeNear(std::vector<MapComponent> regions, int margin_rows,
                                    int margin_cols) {
  for (bool merged = true; merged;) {
    merged = false;
    for (std::size_t i = 0; i < regions.size() && !merged; ++i) {
      for (std::size_t j = i + 1; j < regions.size() && !merged; ++j) {
        if (!Near(regions[i], regions[j], margin_rows, margin_cols)) continue;
        regions[i].cells.insert(regions[i].cells.end(), regions[j].cells.begin(),
                                regions[j].cells.end());
        Grow(regions[i], regions[j]);
        regions.erase(regions.begin() + static_cast<std::ptrdiff_t>(j));
        merged = true;
      }
    }
  }
  return regions;
}

}  // namespace

std::vector<cv::Point> InteriorCells(const std::vector<cv::Point>& cells, int radius_rows,
                                     int radius_cols) {
  if (cells.empty()) return {};
  cv::Rect box = cv::boundingRect(cells);
  // Padded so that the outside of the box erodes like any cell outside the region.
  const cv::Point pad(radius_cols + 1, radius_rows + 1);
  cv::Mat1b mask = cv::Mat1b::zeros(box.height + 2 * pad.y, box.width + 2 * pad.x);
  const cv::Point origin = box.tl() - pad;
  for (const cv::Point& p : cells) mask(p - origin) = 255;
  const cv::Mat kernel =
      cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * radius_cols + 1, 2 * radius_rows + 1});
  cv::Mat1b eroded;
  cv::erode(mask, eroded, kernel);
  std::vector<cv::Point> inner;
  for (const cv::Point& p : cells) {
    if (eroded(p - origin)) inner.push_back(p);
  }
  return inner;
}

std::vector<Observation> FindDefects(const CoarseMap& map, const cv::Mat1f& residual,
                                     double radius_mm, double nominal_diameter_mm, double sigma_mm,
                                     const DefectOptions& options) {
  options.Check();
  const Wall wall{map, radius_mm};
  const double min_cells = options.min_area_mm2 / wall.CellMm2();
  const double in_high = std::max(options.intrusion_mm, options.noise_factor * sigma_mm);
  const double out_high = std::max(options.surface_mm, options.noise_factor * sigma_mm);
  std::vector<MapComponent> inward = HysteresisComponents(residual, -1.0, 0.5 * in_high, in_high);
  std::vector<MapComponent> outward = HysteresisComponents(residual, 1.0, 0.5 * out_high, out_high);
  // Connections: bores first, then every region next to one joins it.
  std::vector<bool> used_in(inward.size(), false), used_out(outward.size(), false);
  const int margin_rows = static_cast<int>(options.connection_margin_mm / wall.RowMm());
  const int margin_cols = static_cast<int>(options.connection_margin_mm / wall.ColMm());
  std::vector<MapComponent> bores;
  for (std::size_t i = 0; i < outward.size(); ++i) {
    if (Percentile(SignedValues(residual, wall, outward[i].cells, 1.0), 0.9) <
        options.bore_depth_mm)
      continue;
    used_out[i] = true;
    bores.push_back(outward[i]);
  }
  // Parts of one bore split by unmeasured cells, and the regions next to a bore, join it.
  std::vector<ConnectionParts> connections;
  for (const MapComponent& bore : MergeNear(std::move(bores), margin_rows, margin_cols)) {
    // A few cells far outward (a depth map's wrongly decoded island) are no lateral's bore.
    if (static_cast<double>(bore.cells.size()) < min_cells) continue;
    connections.push_back({bore.cells, {}, bore});
  }
  auto join = [&](std::vector<MapComponent>& regions, std::vector<bool>& used,
                  ConnectionParts& parts, std::vector<cv::Point>& into) {
    for (std::size_t j = 0; j < regions.size(); ++j) {
      if (used[j] || !Near(regions[j], parts.box, margin_rows, margin_cols)) continue;
      used[j] = true;
      into.insert(into.end(), regions[j].cells.begin(), regions[j].cells.end());
      Grow(parts.box, regions[j]);
    }
  };
  for (ConnectionParts& parts : connections) {
    join(outward, used_out, parts, parts.bore);
    join(inward, used_in, parts, parts.ring);
  }
  std::vector<Observation> out;
  for (const ConnectionParts& c : connections) {
    out.push_back(Connection(wall, residual, c, nominal_diameter_mm, in_high));
  }
  // A deposit's bed is one region, its ramps' measured islands (split from it by the steep
  // ramp's lost spots) with it.
  std::vector<MapComponent> bed, obstacles;
  for (std::size_t i = 0; i < inward.size(); ++i) {
    if (used_in[i]) continue;
    const MapComponent& c = inward[i];
    const double clock = ClockRadToHours(wall.Clock(0.5 * (c.col_min + c.col_max)));
    (std::abs(clock - 6.0) <= options.invert_half_h ? bed : obstacles).push_back(c);
  }
  for (const MapComponent& c :
       MergeNear(std::move(bed), static_cast<int>(options.deposit_join_mm / wall.RowMm()),
                 static_cast<int>(options.deposit_join_mm / wall.ColMm()))) {
    if (static_cast<double>(c.cells.size()) >= min_cells)
      out.push_back(Deposit(wall, residual, c, nominal_diameter_mm, in_high));
  }
  for (const MapComponent& c : obstacles) {
    if (static_cast<double>(c.cells.size()) < min_cells) continue;
    const double height = Percentile(SignedValues(residual, wall, c.cells, -1.0), 0.9);
    Observation o = Describe(wall, residual, c, -1.0, height, in_high);
    o.code = "BBE";
    o.quantities = {{"height_mm", height, "mm"},
                    {"area_mm2", static_cast<double>(c.cells.size()) * wall.CellMm2(), "mm2"}};
    o.remark = fmt::format("obstacle standing {:.1f} mm from the wall", height);
    out.push_back(o);
  }
  // A rough spalled floor loses spots: its measured islands, and the holes between them,
  // are one region.
  std::vector<MapComponent> surfaces;
  for (std::size_t i = 0; i < outward.size(); ++i) {
    if (!used_out[i]) surfaces.push_back(outward[i]);
  }
  surfaces = JoinThroughHoles(surfaces, map.displacement_mm,
                              static_cast<int>(options.max_hole_mm / wall.RowMm()),
                              static_cast<int>(options.max_hole_mm / wall.ColMm()));
  for (const MapComponent& c : surfaces) {
    if (static_cast<double>(c.cells.size()) >= min_cells)
      out.push_back(Surface(wall, residual, c, options, out_high));
  }
  return out;
}

void DefectOptions::Check() const {
  ValidatePositive("intrusion_mm", intrusion_mm);
  ValidatePositive("surface_mm", surface_mm);
  ValidateNotNegative("noise_factor", noise_factor);
  ValidateNotNegative("min_area_mm2", min_area_mm2);
  ValidatePositive("crack_elongation", crack_elongation);
  ValidatePositive("crack_max_width_mm", crack_max_width_mm);
  ValidatePositive("bore_depth_mm", bore_depth_mm);
  ValidateNotNegative("deposit_join_mm", deposit_join_mm);
  ValidateNotNegative("connection_margin_mm", connection_margin_mm);
  SEWER3D_VALIDATE(invert_half_h > 0.0 && invert_half_h <= 6.0, "invert_half_h",
                   "must be in (0, 6] h, got " << invert_half_h);
  ValidateNotNegative("spall_rim_mm", spall_rim_mm);
  ValidateNotNegative("max_hole_mm", max_hole_mm);
}

}  // namespace sewer3d
