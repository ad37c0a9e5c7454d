#include "sewer3d/pattern/codebook.hpp"

#include <gtest/gtest.h>

#include <bit>

#include "sewer3d/pattern/default_pattern.hpp"

namespace sewer3d {
namespace {

TEST(Codebook, EveryWindowOfTheTiledImageDecodesToItsPosition) {
  const BinaryArray array = DefaultPatternArray();
  const Codebook codebook(array, PatternConstraints{});
  EXPECT_EQ(codebook.size(), 1200u);
  // Windows anywhere in the tiling (across tile seams too) decode to the position mod size.
  for (int r = -7; r < 20; ++r) {
    for (int c = -9; c < 420; c += 3) {
      const auto hit = codebook.Find(TiledWindowCode(array, r, c, 6));
      ASSERT_TRUE(hit.has_value()) << r << "," << c;
      EXPECT_EQ(hit->row, ((r % 6) + 6) % 6);
      EXPECT_EQ(hit->col, ((c % 200) + 200) % 200);
    }
  }
}

TEST(Codebook, CorrectsEverySingleBitError) {
  const BinaryArray array = DefaultPatternArray();
  const Codebook codebook(array, PatternConstraints{});
  for (int r = 0; r < array.rows; ++r) {
    for (int c = 0; c < array.cols; ++c) {
      const std::uint64_t code = TiledWindowCode(array, r, c, 6);
      for (int b = 0; b < 36; ++b) {
        const auto match = codebook.Decode(code ^ (std::uint64_t{1} << b));
        ASSERT_TRUE(match.has_value());
        EXPECT_EQ(match->position, (ArrayPosition{r, c}));
        EXPECT_EQ(match->corrected_bits, 1);
        EXPECT_EQ(match->codeword, code);
      }
    }
  }
}

TEST(Codebook, DoubleErrorsNeverDecodeFartherThanOneBit) {
  const BinaryArray array = DefaultPatternArray();
  const Codebook codebook(array, PatternConstraints{});
  int rejected = 0;
  for (int c = 0; c < array.cols; ++c) {
    const std::uint64_t code = TiledWindowCode(array, 0, c, 6) ^ 0b1000001;
    const auto match = codebook.Decode(code);
    if (!match) {
      ++rejected;
      continue;
    }
    EXPECT_LE(std::popcount(match->codeword ^ code), 1);
    EXPECT_NE(match->position, (ArrayPosition{0, c}));
  }
  EXPECT_GT(rejected, array.cols / 2);  // most double errors are detected, not miscorrected
}

TEST(Codebook, RejectsArrayWithRepeatedWindows) {
  const BinaryArray empty(6, 12);
  EXPECT_THROW(Codebook(empty, PatternConstraints{}), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
