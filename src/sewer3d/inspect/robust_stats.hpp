#pragma once
/// \file
/// Order statistics the inspection's robust fits and measures share.

#include <utility>
#include <vector>

namespace sewer3d {

/// The q-quantile (0..1, nearest rank) of `values`; NaN when empty.
double Percentile(std::vector<double> values, double q);
/// The median (upper middle for an even count); NaN when empty.
inline double Median(std::vector<double> values) { return Percentile(std::move(values), 0.5); }

}  // namespace sewer3d
