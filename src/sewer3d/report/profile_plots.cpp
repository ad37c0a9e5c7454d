#include "sewer3d/report/profile_plots.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sewer3d/report/html.hpp"

namespace sewer3d {
namespace {

constexpr double kWidth = 900, kHeight = 260, kLeft = 70, kRight = 150, kTop = 12, kBottom = 42;

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void Add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  void Widen() {
    if (!std::isfinite(lo)) lo = 0.0, hi = 1.0;
    if (hi - lo < 1e-9) lo -= 0.5, hi += 0.5;
  }
};

std::string Polylines(const std::vector<double>& x, const std::vector<double>& y, const Range& rx,
                      const Range& ry, const std::string& colour) {
  auto px = [&](double v) {
    return kLeft + (v - rx.lo) / (rx.hi - rx.lo) * (kWidth - kLeft - kRight);
  };
  auto py = [&](double v) {
    return kHeight - kBottom - (v - ry.lo) / (ry.hi - ry.lo) * (kHeight - kTop - kBottom);
  };
  std::string out, points;
  auto flush = [&] {
    if (!points.empty())
      out += "<polyline fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"1.5\" points=\"" +
             points + "\"/>";
    points.clear();
  };
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (!std::isfinite(y[i])) {
      flush();
      continue;
    }
    points += fmt::format("{:.1f},{:.1f} ", px(x[i]), py(y[i]));
  }
  flush();
  return out;
}

std::string Axes(const Range& rx, const Range& ry, const std::string& x_label,
                 const std::string& y_label) {
  const double w = kWidth - kLeft - kRight, h = kHeight - kTop - kBottom;
  std::string out = fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#888\"/>", kLeft,
      kTop, w, h);
  for (const double t : NiceTicks(rx.lo, rx.hi, 8)) {
    const double x = kLeft + (t - rx.lo) / (rx.hi - rx.lo) * w;
    out += fmt::format(
        "<line x1=\"{0:.1f}\" x2=\"{0:.1f}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#ddd\"/>"
        "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4:g}</text>",
        x, kTop, kTop + h, kTop + h + 16, t);
  }
  for (const double t : NiceTicks(ry.lo, ry.hi, 5)) {
    const double y = kTop + h - (t - ry.lo) / (ry.hi - ry.lo) * h;
    out += fmt::format(
        "<line x1=\"{0}\" x2=\"{1}\" y1=\"{2:.1f}\" y2=\"{2:.1f}\" stroke=\"#ddd\"/>"
        "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:g}</text>",
        kLeft, kLeft + w, y, kLeft - 6, y + 4, t);
  }
  out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>", kLeft + w / 2,
                     kHeight - 6, html::Escape(x_label));
  out += fmt::format(
      "<text x=\"14\" y=\"{}\" transform=\"rotate(-90 14 {})\" "
      "text-anchor=\"middle\">{}</text>",
      kTop + h / 2, kTop + h / 2, html::Escape(y_label));
  return out;
}

}  // namespace

std::vector<double> NiceTicks(double lo, double hi, int count) {
  std::vector<double> ticks;
  if (!(hi > lo) || count < 1) return ticks;
  const double raw = (hi - lo) / count;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * decade;
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * decade >= raw) {
      step = m * decade;
      break;
    }
  }
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step)
    ticks.push_back(std::abs(t) < 1e-9 * step ? 0.0 : t);
  return ticks;
}

std::string LinePlotSvg(const std::vector<double>& x, const std::string& x_label,
                        const std::vector<PlotSeries>& series, const std::string& y_label) {
  Range rx, ry;
  for (const double v : x) rx.Add(v);
  for (const PlotSeries& s : series) {
    for (const double v : s.y) ry.Add(v);
  }
  rx.Widen();
  ry.Widen();
  std::string out = fmt::format("<svg class=\"plot\" viewBox=\"0 0 {} {}\">", kWidth, kHeight);
  out += Axes(rx, ry, x_label, y_label);
  for (std::size_t k = 0; k < series.size(); ++k) {
    out += Polylines(x, series[k].y, rx, ry, series[k].colour);
    const double y = kTop + 14 + 18.0 * static_cast<double>(k);
    out += fmt::format(
        "<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"{3}\" "
        "stroke-width=\"2\"/><text x=\"{4}\" y=\"{5}\">{6}</text>",
        kWidth - kRight + 10, kWidth - kRight + 30, y, series[k].colour, kWidth - kRight + 36,
        y + 4, html::Escape(series[k].label));
  }
  return out + "</svg>\n";
}

std::string StandaloneSvg(const std::string& inline_svg) {
  const std::string head = "<svg class=\"plot\"";
  if (inline_svg.rfind(head, 0) != 0) return inline_svg;
  const std::size_t end = inline_svg.find('>');
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" font-family=\"sans-serif\" font-size=\"12\"" +
         inline_svg.substr(head.size(), end - head.size()) + ">" +
         "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>" + inline_svg.substr(end + 1);
}

std::string ProfilePlots(const Profile& profile) {
  std::vector<double> x;
  PlotSeries mean{"mean", "#1f5fbf", {}}, lo{"min", "#8fb0e0", {}}, hi{"max", "#e08f8f", {}};
  PlotSeries en{"EN 13508-2", "#1f5fbf", {}}, astm{"ASTM F1216", "#c0392b", {}};
  for (const ProfileRow& r : profile.rows) {
    x.push_back(r.station_mm / 1000.0);
    mean.y.push_back(r.mean_diameter_mm);
    lo.y.push_back(r.min_diameter_mm);
    hi.y.push_back(r.max_diameter_mm);
    en.y.push_back(r.ovality_en_pct);
    astm.y.push_back(r.ovality_astm_pct);
  }
  return LinePlotSvg(x, "station (m)", {mean, lo, hi}, "diameter (mm)") +
         LinePlotSvg(x, "station (m)", {en, astm}, "ovality (%)");
}

}  // namespace sewer3d
