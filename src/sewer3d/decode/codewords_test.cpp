// Window voting on a synthetic lattice: every spot of a patch of the shipped array at its
// true node, then one spot's label slipped by one column (what a lattice seam at a depth step
// or a steep pit rim does). Its neighbours' windows still decode (one bit corrected), and must
// not hand it their offset: it would triangulate one column — about 1.3 mm — off.

#include "sewer3d/decode/codewords.hpp"

#include <gtest/gtest.h>

#include "sewer3d/pattern/constraints.hpp"
#include "sewer3d/pattern/default_pattern.hpp"

namespace sewer3d {
namespace {

struct Patch {
  std::vector<Spot> spots;
  LatticeLabels lattice;
  std::vector<Eigen::Vector2i> truth;  // array (row, col) per spot
};

// Spots of tiled rows [0, rows) and columns [c0, c0 + cols) on an 8 px grid filling an image
// of kImage (windows reaching past the patch are outside it, hence unobservable); lattice
// nodes shifted by an arbitrary offset, as a real group's are.
const cv::Size kImage(240, 144);
Patch MakePatch(const BinaryArray& array, int rows, int c0, int cols) {
  Patch p;
  for (int r = 0; r < rows; ++r) {
    for (int c = c0; c < c0 + cols; ++c) {
      if (!array.tiled(r, c)) continue;
      p.spots.push_back({Eigen::Vector2d(4.0 + 8.0 * (c - c0), 4.0 + 8.0 * r), 12, 50.0});
      p.truth.emplace_back(r % array.rows, c % array.cols);
      p.lattice.group.push_back(0);
      p.lattice.node.emplace_back(r + 37, c - c0 - 11);
      p.lattice.steps.push_back({Eigen::Vector2d(8.0, 0.0), Eigen::Vector2d(0.0, 8.0)});
    }
  }
  p.lattice.groups = 1;
  return p;
}

TEST(Codewords, EverySpotOfACleanPatchGetsItsArrayPosition) {
  const BinaryArray array = DefaultPatternArray();
  const Codebook codebook(array, InferConstraints(array));
  const Patch p = MakePatch(array, 18, 40, 30);
  CodewordStats stats;
  const auto codes =
      DecodeCodewords(p.spots, p.lattice, codebook, array.rows, array.cols, kImage, {}, &stats);
  EXPECT_EQ(stats.bits_corrected, 0);
  int interior = 0;
  for (const SpotCode& c : codes) {
    EXPECT_EQ(Eigen::Vector2i(c.row, c.col), p.truth[c.spot]);
    ++interior;
  }
  EXPECT_GT(interior, 0.8 * p.spots.size());
}

TEST(Codewords, ASlippedLabelIsNotDecoded) {
  const BinaryArray array = DefaultPatternArray();
  const Codebook codebook(array, InferConstraints(array));
  Patch p = MakePatch(array, 18, 40, 30);
  // Slip a spot in the middle of the patch by one lattice column.
  int slipped = -1;
  for (size_t i = 0; i < p.spots.size(); ++i) {
    const Eigen::Vector2d& c = p.spots[i].centre_px;
    if (c.x() > 100.0 && c.x() < 140.0 && c.y() > 60.0 && c.y() < 90.0) {
      slipped = static_cast<int>(i);
      break;
    }
  }
  ASSERT_GE(slipped, 0);
  p.lattice.node[slipped].y() += 1;
  CodewordStats stats;
  const auto codes =
      DecodeCodewords(p.spots, p.lattice, codebook, array.rows, array.cols, kImage, {}, &stats);
  EXPECT_GT(stats.bits_corrected, 0);  // neighbours' windows saw the slip and corrected it
  int right = 0;
  for (const SpotCode& c : codes) {
    EXPECT_NE(c.spot, slipped) << "the slipped spot took its neighbours' offset";
    EXPECT_EQ(Eigen::Vector2i(c.row, c.col), p.truth[c.spot]);
    right += Eigen::Vector2i(c.row, c.col) == p.truth[c.spot];
  }
  EXPECT_GT(right, 0.7 * p.spots.size());
}

}  // namespace
}  // namespace sewer3d
