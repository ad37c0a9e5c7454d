#pragma once
/// \file
/// Multi-index hashing for small Hamming radii (Norouzi et al. 2012): a code is split into
/// m >= radius + 1 chunks; two codes within distance `radius` agree exactly on at least one
/// chunk (pigeonhole), so a query only scans m buckets.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sewer3d {

class HammingIndex {
 public:
  /// Codes of `bits` bits (<= 64), ids in [0, capacity), queries up to distance `radius`.
  HammingIndex(int bits, int radius, int capacity);

  void Insert(int id, std::uint64_t code);
  void Remove(int id);
  bool Contains(int id) const { return present_[id] != 0; }

  /// Calls f(id) once for every stored id whose code is within `radius` of x.
  template <class F>
  void ForEachWithin(std::uint64_t x, F&& f) const {
    for (int k = 0; k < chunks_; ++k) {
      const std::uint32_t key = Key(x, k);
      for (int id : buckets_[Bucket(k, key)]) {
        const std::uint64_t code = codes_[id];
        if (std::popcount(x ^ code) > radius_) continue;
        bool seen_earlier = false;  // report each id at its first matching chunk only
        for (int j = 0; j < k && !seen_earlier; ++j) seen_earlier = Key(code, j) == Key(x, j);
        if (!seen_earlier) f(id);
      }
    }
  }

  int CountWithin(std::uint64_t x) const {
    int n = 0;
    ForEachWithin(x, [&n](int) { ++n; });
    return n;
  }

 private:
  std::uint32_t Key(std::uint64_t code, int k) const {
    return static_cast<std::uint32_t>((code >> shift_[k]) & mask_[k]);
  }
  std::size_t Bucket(int k, std::uint32_t key) const { return offset_[k] + key; }

  int radius_;
  int chunks_;
  std::vector<int> shift_;
  std::vector<std::uint64_t> mask_;
  std::vector<std::size_t> offset_;
  std::vector<std::vector<int>> buckets_;
  std::vector<std::uint64_t> codes_;
  std::vector<std::uint8_t> present_;
};

}  // namespace sewer3d
