#pragma once
/// \file
/// Constraints of a perfect-submap spot array (Morano et al. 1998, as used by the paper)
/// and an independent brute-force verifier.

#include <cstdint>
#include <string>

#include "sewer3d/pattern/binary_array.hpp"

namespace sewer3d {

/// What a valid pattern array must satisfy.
struct PatternConstraints {
  int window = 6;        ///< side of the square codeword window, elements (2..8)
  int min_hamming = 3;   ///< every pair of windows differs in at least this many bits
  int min_weight = 4;    ///< every window holds at least this many spots
  bool isolated = true;  ///< no two spots are 8-adjacent
  /// Windows and adjacency wrap around both edges, so every window of the tiled projector
  /// image is a codeword (not only those that lie inside one tile).
  bool torus = true;

  void Check() const;
};

/// What the verifier found. `valid` is true when every constraint holds.
struct PatternReport {
  int rows = 0, cols = 0;
  int windows = 0;                   ///< windows checked (rows*cols on a torus)
  std::int64_t duplicate_pairs = 0;  ///< pairs of identical windows (up to windows^2 / 2)
  std::int64_t close_pairs = 0;      ///< pairs closer than min_hamming (duplicates included)
  int min_hamming_found = 0;  ///< smallest pairwise distance (window*window+1 if < 2 windows)
  int min_weight_found = 0;   ///< lightest window
  int max_weight_found = 0;
  std::int64_t adjacent_spot_pairs = 0;  ///< 8-adjacent spot pairs (with wrap on a torus)
  double density = 0.0;                  ///< spots per element
  bool valid = false;
};

/// Number of windows an array of this size has under the constraints' wrap rule.
int WindowCount(int rows, int cols, const PatternConstraints& constraints);

/// Checks every constraint by brute force (all pairs of windows). Independent of the search.
PatternReport VerifyPattern(const BinaryArray& array, const PatternConstraints& constraints);

/// The constraints an existing array satisfies, for decoding a module file's matrix: torus
/// when its wrap-around windows are unique, else plain; the minimum distance and weight
/// found. Throws std::invalid_argument when even the plain windows repeat.
PatternConstraints InferConstraints(const BinaryArray& array, int window = 6);

/// One-line summary such as "8x168 torus, 1344 windows, min Hamming 3, ...".
std::string Describe(const PatternReport& report);

}  // namespace sewer3d
