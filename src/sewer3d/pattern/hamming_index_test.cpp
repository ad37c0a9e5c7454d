#include "sewer3d/pattern/hamming_index.hpp"

#include <gtest/gtest.h>

#include <random>

namespace sewer3d {
namespace {

TEST(HammingIndex, MatchesBruteForce) {
  std::mt19937_64 rng(3);
  for (int radius : {0, 1, 2, 3}) {
    constexpr int kBits = 36, kCount = 3000;
    HammingIndex index(kBits, radius, kCount);
    std::vector<std::uint64_t> codes(kCount);
    for (int i = 0; i < kCount; ++i) {
      // Sparse codes cluster, as pattern windows do.
      codes[i] = rng() & rng() & rng() & ((std::uint64_t{1} << kBits) - 1);
      index.Insert(i, codes[i]);
    }
    for (int i = 0; i < kCount; i += 2) index.Remove(i);
    for (int q = 0; q < 300; ++q) {
      const std::uint64_t x = codes[rng() % kCount] ^ (std::uint64_t{1} << (rng() % kBits));
      int expected = 0;
      for (int i = 1; i < kCount; i += 2) expected += std::popcount(x ^ codes[i]) <= radius;
      std::vector<int> seen;
      index.ForEachWithin(x, [&](int id) { seen.push_back(id); });
      EXPECT_EQ(static_cast<int>(seen.size()), expected) << "radius " << radius;
      std::sort(seen.begin(), seen.end());
      EXPECT_EQ(std::adjacent_find(seen.begin(), seen.end()), seen.end()) << "reported twice";
    }
  }
}

}  // namespace
}  // namespace sewer3d
