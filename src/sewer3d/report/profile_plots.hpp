#pragma once
/// \file
/// Line plots as inline SVG (no script needed): the profile's mean diameter and ovality along
/// the pipe.

#include <string>
#include <vector>

#include "sewer3d/inspect/profile.hpp"

namespace sewer3d {

struct PlotSeries {
  std::string label;
  std::string colour;     ///< CSS colour
  std::vector<double> y;  ///< one per x; NaN breaks the line
};

/// An SVG line plot of `series` over `x` (same length), with ticks on both axes.
std::string LinePlotSvg(const std::vector<double>& x, const std::string& x_label,
                        const std::vector<PlotSeries>& series, const std::string& y_label);

/// LinePlotSvg's inline SVG as a file of its own (the SVG namespace, a white background).
std::string StandaloneSvg(const std::string& inline_svg);

/// "1, 2 or 5 × 10^k" tick positions covering [lo, hi] (about `count` of them).
std::vector<double> NiceTicks(double lo, double hi, int count);

/// The profile's two plots: mean diameter (with min/max) and ovality (EN, ASTM) over station (m).
std::string ProfilePlots(const Profile& profile);

}  // namespace sewer3d
