#pragma once
/// \file
/// Search for a perfect-submap spot array (paper §pattern; Morano et al. 1998): every
/// window x window sub-array unique, pairwise Hamming distance >= min_hamming, window weight
/// >= min_weight, no two spots 8-adjacent.
///
/// Plain depth-first backtracking stalls near 8 x 100 elements with these constraints
/// (DESIGN.md). This search is a min-conflicts local search with tabu on the whole array:
/// the cost is (pairs of windows closer than min_hamming) + (missing spots below
/// min_weight, summed over windows); isolation is kept as an invariant of every move.
/// Conflicting pairs are found with multi-index hashing, so a move costs O(window²) queries.

#include <cstdint>
#include <functional>
#include <string>

#include "sewer3d/pattern/binary_array.hpp"
#include "sewer3d/pattern/constraints.hpp"

namespace sewer3d {

/// Periodic state of a running search, for progress display.
struct SubmapSearchProgress {
  std::int64_t moves = 0;
  int cost = 0;
  int best_cost = 0;
  int violated_windows = 0;
  double elapsed_s = 0.0;
};

struct SubmapSearchOptions {
  int rows = 8;
  int cols = 64;
  PatternConstraints constraints;
  std::uint64_t seed = 1;
  /// Deterministic budget: the search stops after this many moves.
  std::int64_t max_moves = 2'000'000;
  /// Safety budget in wall-clock seconds (<= 0: none). Hitting it makes the result
  /// depend on machine speed, so the result says which budget ended the search.
  double max_seconds = 0.0;
  /// Probability of a random instead of the best candidate move.
  double noise = 0.05;
  /// A changed element may not change back for tabu_tenure (+ random up to as much) moves.
  int tabu_tenure = 8;
  /// Called about every progress_interval_moves moves; return false to stop the search.
  std::function<bool(const SubmapSearchProgress&)> progress;
  std::int64_t progress_interval_moves = 100'000;

  void Check() const;
};

struct SubmapSearchResult {
  BinaryArray array;     ///< the best array found (valid only when `reached`)
  bool reached = false;  ///< all constraints hold
  /// Cost of `array` (0 when reached); −1 when the time budget ended during the set-up, before
  /// the first cost was known.
  int final_cost = 0;
  std::int64_t moves = 0;
  double elapsed_s = 0.0;
  std::string termination;  ///< "reached", "move budget", "time budget" or "stopped"
};

/// Runs the search. Deterministic for a seed unless the time budget or the callback stops it.
SubmapSearchResult SearchPerfectSubmap(const SubmapSearchOptions& options);

}  // namespace sewer3d
