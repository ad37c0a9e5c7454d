#pragma once
/// \file
/// The JSON written beside a pattern matrix: the parameters it was searched with and the
/// properties the verifier confirmed.

#include <filesystem>

#include "sewer3d/pattern/constraints.hpp"
#include "sewer3d/pattern/submap_search.hpp"

namespace sewer3d {

/// How the matrix came to be: a search run, or the array shipped with sewer3d.
struct PatternProvenance {
  const SubmapSearchOptions* options = nullptr;  ///< parameters (required)
  const SubmapSearchResult* result = nullptr;    ///< search statistics, if searched now
  const char* source = "search";                 ///< "search" or "shipped"
};

/// The sidecar's path for a matrix path: same folder and stem, extension .json.
std::filesystem::path PatternSidecarPath(const std::filesystem::path& matrix_path);

/// Writes the sidecar JSON. Throws FileError when the file cannot be written.
void WritePatternSidecar(const std::filesystem::path& path, const PatternProvenance& provenance,
                         const PatternReport& report);

}  // namespace sewer3d
