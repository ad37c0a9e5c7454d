#include "sewer3d/pattern/codebook.hpp"

#include <algorithm>
#include <bit>

namespace sewer3d {

Codebook::Codebook(const BinaryArray& array, const PatternConstraints& constraints)
    : window_(constraints.window), min_hamming_(constraints.min_hamming) {
  constraints.Check();
  const int n = constraints.window;
  const int win_rows = constraints.torus ? array.rows : array.rows - n + 1;
  const int win_cols = constraints.torus ? array.cols : array.cols - n + 1;
  SEWER3D_VALIDATE(win_rows > 0 && win_cols > 0, "",
                   "the pattern (" << array.rows << "x" << array.cols
                                   << ") is smaller than its window (" << n << "x" << n << ")");
  table_.reserve(static_cast<std::size_t>(win_rows) * win_cols);
  for (int r = 0; r < win_rows; ++r) {
    for (int c = 0; c < win_cols; ++c) {
      const auto [it, inserted] =
          table_.emplace(TiledWindowCode(array, r, c, n), ArrayPosition{r, c});
      SEWER3D_VALIDATE(inserted, "",
                       "the pattern's window at (" << r << ", " << c << ") repeats the one at ("
                                                   << it->second.row << ", " << it->second.col
                                                   << ")");
      const int weight = std::popcount(it->first);
      min_weight_ = std::min(min_weight_, weight);
      max_weight_ = std::max(max_weight_, weight);
    }
  }
}

std::optional<ArrayPosition> Codebook::Find(std::uint64_t code) const {
  const auto it = table_.find(code);
  if (it == table_.end()) return std::nullopt;
  return it->second;
}

std::optional<CodewordMatch> Codebook::Decode(std::uint64_t code, int max_corrected_bits) const {
  SEWER3D_VALIDATE(max_corrected_bits >= 0 && max_corrected_bits <= 1, "max_corrected_bits",
                   "must be 0 or 1 (single-bit correction), got " << max_corrected_bits);
  SEWER3D_VALIDATE(2 * max_corrected_bits < min_hamming_, "max_corrected_bits",
                   "correcting " << max_corrected_bits
                                 << " bit(s) needs a minimum Hamming distance > "
                                 << 2 * max_corrected_bits << ", the pattern has " << min_hamming_);
  // No codeword within reach of a word whose weight is too far from theirs: skips the 36
  // flipped lookups for most words that cannot decode (empty or crowded windows).
  const int weight = std::popcount(code);
  if (weight < min_weight_ - max_corrected_bits || weight > max_weight_ + max_corrected_bits)
    return std::nullopt;
  if (const auto exact = Find(code)) return CodewordMatch{*exact, code, 0};
  if (max_corrected_bits == 0) return std::nullopt;
  const int bits = window_ * window_;
  for (int b = 0; b < bits; ++b) {
    const std::uint64_t candidate = code ^ (std::uint64_t{1} << b);
    if (const auto hit = Find(candidate)) return CodewordMatch{*hit, candidate, 1};
  }
  return std::nullopt;
}

}  // namespace sewer3d
