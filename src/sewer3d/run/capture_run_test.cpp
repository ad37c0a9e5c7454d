#include "sewer3d/run/capture_run.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace sewer3d {
namespace {

TEST(ImageKind, NamesRoundTrip) {
  for (const ImageKind k : kImageKinds) EXPECT_EQ(ParseImageKind(ImageKindName(k)), k);
  EXPECT_FALSE(ParseImageKind("texture"));
  EXPECT_FALSE(ParseImageKind(""));
  EXPECT_EQ(ImageStem(3, 42, ImageKind::kTextureAfter), "m3/000042_texture_after");
}

TEST(GroupAcquisitions, TripletsByModuleAndCounter) {
  const std::vector<RunImage> images = {
      {1, 0, ImageKind::kTextureBefore, 0.020, 2.0, "a"},
      {0, 0, ImageKind::kTextureBefore, 0.000, 2.0, "b"},
      {0, 0, ImageKind::kPattern, 0.005, 2.0, "c"},
      {1, 0, ImageKind::kPattern, 0.025, 2.0, "d"},
      {0, 0, ImageKind::kTextureAfter, 0.010, 2.0, "e"},
      {0, 1, ImageKind::kPattern, 0.105, 2.0, "f"},
  };
  const auto acquisitions = GroupAcquisitions(images);
  ASSERT_EQ(acquisitions.size(), 3u);
  EXPECT_EQ(acquisitions[0].module, 0);
  EXPECT_EQ(acquisitions[0].counter, 0);
  EXPECT_EQ(acquisitions[0].Image(ImageKind::kTextureBefore), 1);
  EXPECT_EQ(acquisitions[0].Image(ImageKind::kPattern), 2);
  EXPECT_EQ(acquisitions[0].Image(ImageKind::kTextureAfter), 4);
  EXPECT_EQ(acquisitions[1].counter, 1);
  EXPECT_EQ(acquisitions[1].Image(ImageKind::kTextureBefore), -1);
  EXPECT_EQ(acquisitions[1].Image(ImageKind::kPattern), 5);
  EXPECT_EQ(acquisitions[2].module, 1);
  EXPECT_EQ(acquisitions[2].Image(ImageKind::kTextureAfter), -1);
}

TEST(GroupAcquisitions, RejectsTwoImagesOfOneKind) {
  const std::vector<RunImage> images = {{0, 3, ImageKind::kPattern, 0.0, 2.0, "a"},
                                        {0, 3, ImageKind::kPattern, 0.1, 2.0, "b"}};
  EXPECT_THROW(GroupAcquisitions(images), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
