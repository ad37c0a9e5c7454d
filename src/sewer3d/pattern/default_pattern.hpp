#pragma once
/// \file
/// The pattern array shipped with sewer3d (DESIGN.md: generated once, shipped; the generator
/// stays in the product). A 6 x 200 torus perfect submap: window 6, min Hamming 3, min weight 4,
/// isolated spots, windows wrapping around both edges. docs/pattern.md shows that 200 columns
/// span the default module's disparity range with margin.

#include "sewer3d/pattern/binary_array.hpp"
#include "sewer3d/pattern/submap_search.hpp"

namespace sewer3d {

/// The shipped array.
BinaryArray DefaultPatternArray();

/// Search options that produced the shipped array (seed included): running the search with
/// them reproduces it bit for bit.
SubmapSearchOptions DefaultPatternSearchOptions();

}  // namespace sewer3d
