#pragma once
/// \file
/// A binary spot array (the projector pattern matrix) and its windows.

#include <cstdint>
#include <vector>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

/// Most elements of a pattern matrix sewer3d searches, reads or verifies: VerifyPattern compares
/// every pair of windows (2·10⁹ pairs at this size, a few seconds). The default has 1 200.
inline constexpr int kMaxPatternElements = 1 << 16;

/// rows x cols binary matrix, row-major; 1 = spot. Element (r, c) of the tiled projector
/// image takes the value of (r mod rows, c mod cols) (DESIGN.md, module contract).
struct BinaryArray {
  int rows = 0;
  int cols = 0;
  std::vector<std::uint8_t> bits;  ///< rows * cols values, 0 or 1

  BinaryArray() = default;
  BinaryArray(int rows_in, int cols_in)
      : rows(rows_in), cols(cols_in), bits(static_cast<size_t>(rows_in) * cols_in, 0) {
    SEWER3D_CHECK(rows_in > 0 && cols_in > 0, rows_in << "x" << cols_in);
  }

  std::uint8_t at(int r, int c) const { return bits[static_cast<size_t>(r) * cols + c]; }
  void set(int r, int c, std::uint8_t value) { bits[static_cast<size_t>(r) * cols + c] = value; }
  /// Value at (r, c) of the periodic tiling of this array (any integer r, c).
  std::uint8_t tiled(int r, int c) const {
    const int rr = ((r % rows) + rows) % rows;
    const int cc = ((c % cols) + cols) % cols;
    return at(rr, cc);
  }
  int Weight() const {
    int w = 0;
    for (auto b : bits) w += b;
    return w;
  }
  bool operator==(const BinaryArray&) const = default;
};

/// The window x window bits whose top-left element is (r, c) of the tiling, packed
/// row-major into the low bits: bit (i * window + j) = tiled(r + i, c + j). window <= 8.
inline std::uint64_t TiledWindowCode(const BinaryArray& array, int r, int c, int window) {
  std::uint64_t code = 0;
  for (int i = 0; i < window; ++i) {
    for (int j = 0; j < window; ++j) {
      if (array.tiled(r + i, c + j)) code |= std::uint64_t{1} << (i * window + j);
    }
  }
  return code;
}

}  // namespace sewer3d
