#include "sewer3d/inspect/texture_cracks.hpp"

#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/inspect/components.hpp"
#include "sewer3d/inspect/robust_stats.hpp"

namespace sewer3d {
namespace {

/// A narrow hole reads as dark as a crack's core, in units of the texture's local contrast.
constexpr float kHoleLevel = -3.0F;

/// The grey map's cells: rows along the pipe, columns around it (wrapping).
struct Geometry {
  double row_mm = 0.0;
  double col_mm = 0.0;
  int rows = 0;
  int cols = 0;
  [[nodiscard]] double CellMm() const { return std::min(row_mm, col_mm); }
  [[nodiscard]] double CircumferenceMm() const { return cols * col_mm; }
};

cv::Mat1f Blur(const cv::Mat1f& in, double sigma_mm, const Geometry& g) {
  cv::Mat1f out;
  cv::GaussianBlur(in, out, cv::Size(0, 0), sigma_mm / g.col_mm, sigma_mm / g.row_mm,
                   cv::BORDER_REPLICATE);
  return out;
}

/// Blur for a σ of many cells: on the map shrunk by about σ / 3 cells, then enlarged back
/// (what it gives, a local mean or contrast, varies slowly).
cv::Mat1f WideBlur(const cv::Mat1f& in, double sigma_mm, const Geometry& g) {
  const int k = std::max(1, static_cast<int>(sigma_mm / g.CellMm() / 3.0));
  if (k == 1 || in.rows < 2 * k || in.cols < 2 * k) return Blur(in, sigma_mm, g);
  cv::Mat1f small, out;
  cv::resize(in, small, cv::Size(in.cols / k, in.rows / k), 0.0, 0.0, cv::INTER_AREA);
  const Geometry coarse{g.row_mm * in.rows / small.rows, g.col_mm * in.cols / small.cols,
                        small.rows, small.cols};
  cv::resize(Blur(small, sigma_mm, coarse), out, in.size(), 0.0, 0.0, cv::INTER_LINEAR);
  return out;
}

/// The texture less its local mean over its local contrast (grey levels, at least 1); holes
/// read kHoleLevel. `deep`: the cells near holes too wide for a crack (see hole_mm);
/// `contrast`: the local contrast as a share of the local mean (what one unit is in brightness).
cv::Mat1f Normalised(const cv::Mat1b& grey, const Geometry& g, const TextureCrackOptions& o,
                     cv::Mat1b& deep, cv::Mat1f& contrast) {
  const cv::Mat1b hole = grey == 0;
  cv::Mat1f level, valid;
  grey.convertTo(level, CV_32F);
  cv::Mat1b(grey > 0).convertTo(valid, CV_32F, 1.0 / 255.0);
  const cv::Mat1f mean =
      WideBlur(level, o.background_mm, g) / cv::max(WideBlur(valid, o.background_mm, g), 1e-3);
  cv::Mat1f z = (level - mean).mul(valid);
  cv::Mat1f sd;
  cv::sqrt(WideBlur(z.mul(z), o.contrast_mm, g) / cv::max(WideBlur(valid, o.contrast_mm, g), 1e-3),
           sd);
  sd = cv::max(sd, 1.0);
  z /= sd;
  contrast = sd / cv::max(mean, 1.0);
  z.setTo(kHoleLevel, hole);
  cv::Mat1f dist;
  cv::distanceTransform(hole, dist, cv::DIST_L2, 3);
  const cv::Mat1b far = dist * g.CellMm() > o.hole_mm;
  const int reach = static_cast<int>(std::ceil((o.hole_mm + o.side_mm) / g.CellMm()));
  cv::dilate(far, deep,
             cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * reach + 1, 2 * reach + 1)));
  return z;
}

/// `m` (at least 2 × 2: a strip with its margins) at (x, y), clamped to its edges.
float Bilinear(const cv::Mat1f& m, float x, float y) {
  x = std::clamp(x, 0.0F, static_cast<float>(m.cols) - 1.001F);
  y = std::clamp(y, 0.0F, static_cast<float>(m.rows) - 1.001F);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
  return (1.0F - fy) * ((1.0F - fx) * m(y0, x0) + fx * m(y0, x0 + 1)) +
         fy * ((1.0F - fx) * m(y0 + 1, x0) + fx * m(y0 + 1, x0 + 1));
}

/// Per cell: how much darker it is than both its sides, side_mm away across the local line
/// direction (the Hessian's); 0 in `deep`. `along`: the line's direction per cell (x, y).
cv::Mat1f Darker(const cv::Mat1f& z, const cv::Mat1b& deep, const Geometry& g,
                 const TextureCrackOptions& o, cv::Mat2f& along) {
  const cv::Mat1f smooth = Blur(z, o.line_sigma_mm, g), dz = Blur(z, o.direction_sigma_mm, g);
  cv::Mat1f dxx, dyy, dxy;
  cv::Sobel(dz, dxx, CV_32F, 2, 0, 3);
  cv::Sobel(dz, dyy, CV_32F, 0, 2, 3);
  cv::Sobel(dz, dxy, CV_32F, 1, 1, 3);
  const float side = static_cast<float>(o.side_mm / g.CellMm());
  cv::Mat1f darker(z.size());
  along.create(z.size());
  cv::parallel_for_(cv::Range(0, z.rows), [&](const cv::Range& rows) {
    for (int r = rows.start; r < rows.end; ++r) {
      for (int c = 0; c < z.cols; ++c) {
        // The direction of the largest curvature: across a line.
        const float a = 0.5F * std::atan2(2.0F * dxy(r, c), dxx(r, c) - dyy(r, c));
        const float nx = std::cos(a), ny = std::sin(a);
        along(r, c) = {-ny, nx};
        const float sides = std::min(Bilinear(smooth, c + side * nx, r + side * ny),
                                     Bilinear(smooth, c - side * nx, r - side * ny));
        darker(r, c) = deep(r, c) != 0 ? 0.0F : sides - smooth(r, c);
      }
    }
  });
  return darker;
}

/// Darker averaged ± half_length_mm along each cell's line direction: a crack keeps its
/// response, the material's grains and pores lose theirs; 0 in `deep`.
cv::Mat1f LineResponse(const cv::Mat1f& z, const cv::Mat1b& deep, const Geometry& g,
                       const TextureCrackOptions& o) {
  cv::Mat2f along;
  const cv::Mat1f darker = Darker(z, deep, g, o, along);
  const int reach = static_cast<int>(std::lround(o.half_length_mm / g.CellMm()));
  cv::Mat1f out(z.size());
  cv::parallel_for_(cv::Range(0, z.rows), [&](const cv::Range& rows) {
    for (int r = rows.start; r < rows.end; ++r) {
      for (int c = 0; c < z.cols; ++c) {
        if (deep(r, c) != 0) {
          out(r, c) = 0.0F;
          continue;
        }
        const cv::Vec2f t = along(r, c);
        float sum = 0.0F;
        for (int k = -reach; k <= reach; ++k) sum += Bilinear(darker, c + k * t[0], r + k * t[1]);
        out(r, c) = sum / static_cast<float>(2 * reach + 1);
      }
    }
  });
  return out;
}

/// 2 where the response clears the seed level and, in brightness (times `contrast`),
/// min_darkness; 1 where it clears the grow level; else 0. Levels relative to the median and
/// robust sigma of the response over the cells not in `deep`.
cv::Mat1b Levels(const cv::Mat1f& response, const cv::Mat1f& contrast, const cv::Mat1b& deep,
                 const TextureCrackOptions& o) {
  std::vector<double> sample;
  for (int r = 0; r < response.rows; r += 2) {
    for (int c = r % 4; c < response.cols; c += 3) {
      if (deep(r, c) == 0) sample.push_back(response(r, c));
    }
  }
  cv::Mat1b levels = cv::Mat1b::zeros(response.size());
  if (sample.size() < 100) return levels;
  const double median = Median(sample);
  for (double& v : sample) v = std::abs(v - median);
  const double sigma = std::max(1e-6, 1.4826 * Median(sample));
  for (int r = 0; r < response.rows; ++r) {
    for (int c = 0; c < response.cols; ++c) {
      const double s = (response(r, c) - median) / sigma;
      const bool dark = response(r, c) * contrast(r, c) >= o.min_darkness;
      levels(r, c) =
          deep(r, c) != 0 ? 0 : (s >= o.seed_sigmas && dark ? 2 : (s >= o.grow_sigmas ? 1 : 0));
    }
  }
  return levels;
}

/// LineResponse's levels over the whole grey map, filtered strip by strip (each with margins
/// beyond which the map's ends read as wide holes, and its columns wrapped around).
cv::Mat1b LineLevels(const cv::Mat1b& grey, const Geometry& g, const TextureCrackOptions& o) {
  const double reach_mm = 3.0 * o.contrast_mm + o.side_mm + o.half_length_mm;
  const int margin = static_cast<int>(std::ceil(reach_mm / g.row_mm));
  const int pad = std::min(g.cols, static_cast<int>(std::ceil(reach_mm / g.col_mm)));
  const int strip = std::max(1, static_cast<int>(o.strip_mm / g.row_mm));
  cv::Mat1b levels = cv::Mat1b::zeros(g.rows, g.cols);
  for (int r0 = 0; r0 < g.rows; r0 += strip) {
    const int r1 = std::min(g.rows, r0 + strip);
    const int a = std::max(0, r0 - margin), b = std::min(g.rows, r1 + margin);
    cv::Mat1b wrapped;
    cv::copyMakeBorder(grey.rowRange(a, b), wrapped, 0, 0, pad, pad, cv::BORDER_WRAP);
    cv::Mat1b ext = cv::Mat1b::zeros(r1 - r0 + 2 * margin, g.cols + 2 * pad);
    wrapped.copyTo(ext.rowRange(a - (r0 - margin), b - (r0 - margin)));
    cv::Mat1b deep;
    cv::Mat1f contrast;
    const cv::Mat1f z = Normalised(ext, g, o, deep, contrast);
    const cv::Mat1f response = LineResponse(z, deep, g, o);
    const cv::Rect core(pad, margin, g.cols, r1 - r0);
    Levels(response(core), contrast(core), deep(core), o).copyTo(levels.rowRange(r0, r1));
  }
  return levels;
}

/// The principal axis of a crack's (or a piece's) cells in mm.
CellAxis Axis(const std::vector<cv::Point>& cells, const Geometry& g) {
  return PrincipalAxis(cells, g.row_mm, g.col_mm);
}

double LengthMm(const CellAxis& a, const Geometry& g) { return a.hi - a.lo + g.CellMm(); }

/// A uniform band's width from its cells' variance across it.
double WidthMm(const CellAxis& a) { return std::sqrt(12.0 * a.across_variance_mm2); }

Eigen::Vector2d Mm(const cv::Point& p, const Geometry& g) {
  return {p.y * g.row_mm, p.x * g.col_mm};
}

struct Piece {
  std::vector<cv::Point> cells;
  CellAxis line;
};

/// The whole turns of columns that bring b's cells next to a's.
int TurnShiftCols(const Piece& a, const Piece& b, const Geometry& g) {
  return static_cast<int>(
             std::round((a.line.centre.y() - b.line.centre.y()) / g.CircumferenceMm())) *
         g.cols;
}

/// Whether two pieces are of one crack (TextureCrackOptions' merge_*), b moved next to a.
bool SameCrack(const Piece& a, const Piece& b, const Geometry& g, const TextureCrackOptions& o) {
  const Eigen::Vector2d cb =
      b.line.centre + Eigen::Vector2d(0.0, TurnShiftCols(a, b, g) * g.col_mm);
  const Eigen::Vector2d d = cb - a.line.centre;
  const auto across = [](const Eigen::Vector2d& dir, const Eigen::Vector2d& v) {
    return std::abs(dir.x() * v.y() - dir.y() * v.x());
  };
  if (std::abs(a.line.dir.dot(b.line.dir)) < std::cos(DegToRad(o.merge_angle_deg))) return false;
  if (across(a.line.dir, d) > o.merge_offset_mm || across(b.line.dir, d) > o.merge_offset_mm)
    return false;
  const double tb = d.dot(a.line.dir), s = a.line.dir.dot(b.line.dir) >= 0.0 ? 1.0 : -1.0;
  const double b_lo = tb + std::min(s * b.line.lo, s * b.line.hi);
  const double b_hi = tb + std::max(s * b.line.lo, s * b.line.hi);
  return std::max(b_lo - a.line.hi, a.line.lo - b_hi) <= o.merge_gap_mm;
}

/// The pieces' cells grouped by crack (SameCrack, transitively), each group's columns
/// unwrapped next to its first piece.
std::vector<std::vector<cv::Point>> Cracks(const std::vector<Piece>& pieces, const Geometry& g,
                                           const TextureCrackOptions& o) {
  const int n = static_cast<int>(pieces.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (SameCrack(pieces[i], pieces[j], g, o)) parent[FindRoot(parent, j)] = FindRoot(parent, i);
    }
  }
  std::vector<std::vector<cv::Point>> groups(n);
  std::vector<int> first(n, -1);
  for (int i = 0; i < n; ++i) {
    const int root = FindRoot(parent, i);
    if (first[root] < 0) first[root] = i;
    const int shift = TurnShiftCols(pieces[first[root]], pieces[i], g);
    for (const cv::Point& p : pieces[i].cells) groups[root].emplace_back(p.x + shift, p.y);
  }
  std::erase_if(groups, [](const std::vector<cv::Point>& c) { return c.empty(); });
  return groups;
}

/// The grey level at (along, around) mm (bilinear, columns wrapping); 0 where a hole touches.
double GreyAt(const cv::Mat1b& grey, const Geometry& g, const Eigen::Vector2d& p) {
  const double r = p.x() / g.row_mm, c = p.y() / g.col_mm;
  const int r0 = static_cast<int>(std::floor(r)), c0 = static_cast<int>(std::floor(c));
  if (r0 < 0 || r0 + 1 >= g.rows) return 0.0;
  const double fr = r - r0, fc = c - c0;
  double sum = 0.0;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      const int v = grey(r0 + i, ((c0 + j) % g.cols + g.cols) % g.cols);
      if (v == 0) return 0.0;
      sum += (i ? fr : 1.0 - fr) * (j ? fc : 1.0 - fc) * v;
    }
  }
  return sum;
}

/// The dark line's full width at half its depth below the texture beside it, median over
/// profiles across it every millimetre (a hole counts as black); NaN where none is dark enough.
double ApparentWidthMm(const cv::Mat1b& grey, const Geometry& g, const CellAxis& line) {
  constexpr double kStep = 0.1, kReach = 3.0, kCore = 1.5, kBeside = 2.0, kMinDepth = 10.0;
  const int half = static_cast<int>(kReach / kStep);
  const Eigen::Vector2d across(-line.dir.y(), line.dir.x());
  std::vector<double> widths, profile(2 * half + 1), beside;
  for (double t = line.lo; t <= line.hi; t += 1.0) {
    beside.clear();
    int darkest = half;
    for (int k = -half; k <= half; ++k) {
      const double v = GreyAt(grey, g, line.centre + t * line.dir + k * kStep * across);
      profile[k + half] = v;
      if (std::abs(k * kStep) >= kBeside && v > 0.0) beside.push_back(v);
      if (std::abs(k * kStep) <= kCore && v < profile[darkest]) darkest = k + half;
    }
    if (beside.size() < static_cast<std::size_t>(half / 2)) continue;
    const double level = Median(beside), depth = level - profile[darkest];
    if (depth < kMinDepth) continue;
    int i = darkest, j = darkest;
    while (i > 0 && profile[i - 1] <= level - 0.5 * depth) --i;
    while (j < 2 * half && profile[j + 1] <= level - 0.5 * depth) ++j;
    widths.push_back((j - i + 1) * kStep);
  }
  return Median(widths);
}

/// The observation of a crack's cells (grey map, columns unwrapped).
Observation CrackObservation(const CoarseMap& map, const Geometry& g,
                             const std::vector<cv::Point>& cells, const CellAxis& line,
                             const TextureCrackOptions& o) {
  Observation ob;
  ob.code = "BAB";
  int row_min = cells.front().y, row_max = row_min, col_min = cells.front().x, col_max = col_min;
  for (const cv::Point& p : cells) {
    row_min = std::min(row_min, p.y);
    row_max = std::max(row_max, p.y);
    col_min = std::min(col_min, p.x);
    col_max = std::max(col_max, p.x);
  }
  const double length = LengthMm(line, g);
  ob.station_mm = map.GreyRowStationMm(line.centre.x() / g.row_mm);
  ob.length_mm = (row_max - row_min + 1) * g.row_mm;
  ob.clock_h = ClockRadToHours(map.GreyColClockRad(line.centre.y() / g.col_mm));
  ob.clock_from_h = ClockRadToHours(map.GreyColClockRad(col_min - 0.5));
  ob.clock_to_h = ClockRadToHours(map.GreyColClockRad(col_max + 0.5));
  // Continuity: the share of the crack's millimetres along its line that hold a cell.
  std::vector<char> seen(static_cast<std::size_t>(std::ceil(length)) + 1, 0);
  for (const cv::Point& p : cells) {
    seen[static_cast<std::size_t>((Mm(p, g) - line.centre).dot(line.dir) - line.lo)] = 1;
  }
  const double continuity = static_cast<double>(std::count(seen.begin(), seen.end(), 1)) /
                            static_cast<double>(seen.size());
  ob.confidence = continuity * (1.0 - std::exp(-length / o.min_length_mm));
  const double angle = line.AngleDeg();
  const double width = ApparentWidthMm(map.grey, g, line);
  if (std::isfinite(width)) ob.quantities.push_back({"width_mm", width, "mm"});
  ob.quantities.push_back({"length_mm", length, "mm"});
  ob.quantities.push_back({"angle_deg", angle, "deg"});
  ob.remark = fmt::format("crack {:.0f} mm long at {:.0f}° to the axis, seen in the texture",
                          length, angle);
  const int f = map.grey_factor, margin = static_cast<int>(std::ceil(5.0 / g.row_mm));
  ob.crop.row0 = std::max(0, (row_min - margin) * f);
  ob.crop.rows = std::min(map.fine.rows, (row_max + 1 + margin) * f) - ob.crop.row0;
  ob.crop.col0 = (((col_min - margin) * f) % map.fine.cols + map.fine.cols) % map.fine.cols;
  ob.crop.cols = std::min(map.fine.cols, (col_max - col_min + 1 + 2 * margin) * f);
  return ob;
}

/// Clears the cells of `levels` (grey map) inside the crops (fine map cells).
void Exclude(cv::Mat1b& levels, const CoarseMap& map, const std::vector<MapCrop>& crops) {
  const int f = map.grey_factor;
  for (const MapCrop& c : crops) {
    const int r0 = std::max(0, c.row0 / f);
    const int r1 = std::min(levels.rows, (c.row0 + c.rows + f - 1) / f);
    for (int r = r0; r < r1; ++r) {
      for (int x = c.col0 / f; x < (c.col0 + c.cols + f - 1) / f; ++x)
        levels(r, x % levels.cols) = 0;
    }
  }
}

}  // namespace

void TextureCrackOptions::Check() const {
  ValidatePositive("cell_mm", cell_mm);
  ValidatePositive("background_mm", background_mm);
  ValidatePositive("contrast_mm", contrast_mm);
  ValidatePositive("line_sigma_mm", line_sigma_mm);
  ValidatePositive("direction_sigma_mm", direction_sigma_mm);
  ValidatePositive("side_mm", side_mm);
  ValidatePositive("half_length_mm", half_length_mm);
  ValidatePositive("grow_sigmas", grow_sigmas);
  SEWER3D_VALIDATE(min_darkness >= 0.0 && min_darkness < 1.0, "min_darkness",
                   "must be in [0, 1), got " << min_darkness);
  SEWER3D_VALIDATE(seed_sigmas >= grow_sigmas, "seed_sigmas",
                   "must be ≥ grow_sigmas (" << grow_sigmas << "), got " << seed_sigmas);
  ValidatePositive("min_length_mm", min_length_mm);
  ValidatePositive("max_width_mm", max_width_mm);
  SEWER3D_VALIDATE(merge_angle_deg >= 0.0 && merge_angle_deg < 90.0, "merge_angle_deg",
                   "must be in [0, 90), got " << merge_angle_deg);
  ValidateNotNegative("merge_offset_mm", merge_offset_mm);
  ValidateNotNegative("merge_gap_mm", merge_gap_mm);
  ValidatePositive("hole_mm", hole_mm);
  ValidatePositive("strip_mm", strip_mm);
}

std::vector<Observation> FindTextureCracks(const CoarseMap& map, double radius_mm,
                                           const std::vector<MapCrop>& excluded,
                                           const TextureCrackOptions& options) {
  options.Check();
  std::vector<Observation> out;
  if (!options.enabled || map.grey.empty()) return out;
  const Geometry g{map.GreyRowMm(), map.GreyColMm(radius_mm), map.grey.rows, map.grey.cols};
  cv::Mat1b levels = LineLevels(map.grey, g, options);
  Exclude(levels, map, excluded);
  std::vector<Piece> pieces;
  for (MapComponent& c : HysteresisComponents(levels)) {
    Piece p{std::move(c.cells), {}};
    p.line = Axis(p.cells, g);
    // Shorter than the response's own averaging: a blob (grain, pore), not a line.
    if (LengthMm(p.line, g) >= 2.0 * options.half_length_mm &&
        WidthMm(p.line) <= options.max_width_mm)
      pieces.push_back(std::move(p));
  }
  for (const std::vector<cv::Point>& cells : Cracks(pieces, g, options)) {
    const CellAxis line = Axis(cells, g);
    if (LengthMm(line, g) >= options.min_length_mm)
      out.push_back(CrackObservation(map, g, cells, line, options));
  }
  return out;
}

}  // namespace sewer3d
