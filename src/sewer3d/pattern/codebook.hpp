#pragma once
/// \file
/// Codebook of a perfect-submap array: window bits -> (row, col) of the window's top-left
/// element, with single-bit error correction (a minimum Hamming distance of 3 between
/// codewords leaves at most one codeword at distance 1 from any word).

#include <cstdint>
#include <optional>
#include <unordered_map>

#include "sewer3d/pattern/binary_array.hpp"
#include "sewer3d/pattern/constraints.hpp"

namespace sewer3d {

/// Position of a codeword in the array (top-left element of its window).
struct ArrayPosition {
  int row = 0;
  int col = 0;
  bool operator==(const ArrayPosition&) const = default;
};

/// Result of decoding an observed window.
struct CodewordMatch {
  ArrayPosition position;
  std::uint64_t codeword = 0;  ///< the codeword that matched
  int corrected_bits = 0;      ///< bits that differed between observation and codeword
};

class Codebook {
 public:
  /// Every window of `array` under the constraints' wrap rule becomes a codeword. Throws
  /// std::invalid_argument if two windows are identical (the array is not a perfect submap).
  Codebook(const BinaryArray& array, const PatternConstraints& constraints);

  int window() const { return window_; }
  int min_hamming() const { return min_hamming_; }
  std::size_t size() const { return table_.size(); }

  /// Exact lookup.
  std::optional<ArrayPosition> Find(std::uint64_t code) const;

  /// Nearest codeword within `max_corrected_bits`, which must be < min_hamming / 2 so the
  /// answer is unique. nullopt when no codeword is that close.
  std::optional<CodewordMatch> Decode(std::uint64_t code, int max_corrected_bits = 1) const;

 private:
  int window_;
  int min_hamming_;
  int min_weight_ = 64, max_weight_ = 0;  ///< popcount range of the codewords
  std::unordered_map<std::uint64_t, ArrayPosition> table_;
};

}  // namespace sewer3d
