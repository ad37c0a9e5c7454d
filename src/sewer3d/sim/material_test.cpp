#include "sewer3d/sim/material.hpp"

#include <gtest/gtest.h>

#include <opencv2/features2d.hpp>

namespace sewer3d {
namespace {

constexpr double kPixelMm = 0.1;  // the texture images' scale on the wall

// The albedo rasterised at 0.1 mm per pixel over a 64 × 48 mm patch of the unrolled wall.
cv::Mat3f Raster(Material material, std::uint64_t seed) {
  cv::Mat3f image(480, 640);
  for (int v = 0; v < image.rows; ++v) {
    for (int u = 0; u < image.cols; ++u) {
      const Eigen::Vector3d a =
          MaterialAlbedo(material, seed, Eigen::Vector2d(1000.0 + u * kPixelMm, v * kPixelMm));
      image(v, u) = cv::Vec3f(a.x(), a.y(), a.z());
    }
  }
  return image;
}

cv::Scalar Mean(const cv::Mat3f& image) { return cv::mean(image); }

// SIFT keypoints on the patch's grey level, exposed so that albedo 0.5 is DN 128.
int SiftKeypoints(const cv::Mat3f& image) {
  cv::Mat1f grey(image.size());
  for (int v = 0; v < image.rows; ++v)
    for (int u = 0; u < image.cols; ++u)
      grey(v, u) = (image(v, u)[0] + image(v, u)[1] + image(v, u)[2]) / 3.0f;
  cv::Mat1b grey8;
  grey.convertTo(grey8, CV_8U, 256.0);
  std::vector<cv::KeyPoint> keypoints;
  cv::SIFT::create()->detect(grey8, keypoints);
  return static_cast<int>(keypoints.size());
}

// Fraction of horizontally adjacent pixels whose grey differs by more than 0.05: crisp edges
// (grain outlines, pores, cracks) rather than smooth mottling.
double EdgeDensity(const cv::Mat3f& image) {
  int edges = 0;
  for (int v = 0; v < image.rows; ++v) {
    for (int u = 1; u < image.cols; ++u) {
      const cv::Vec3f d = image(v, u) - image(v, u - 1);
      edges += std::abs(d[0] + d[1] + d[2]) / 3.0 > 0.05;
    }
  }
  return static_cast<double>(edges) / (image.rows * (image.cols - 1));
}

TEST(Material, IsDeterministicForASeed) {
  const Eigen::Vector2d p(123.456, -78.9);
  for (const Material m : {Material::kConcrete, Material::kVitrifiedClay, Material::kPlastic,
                           Material::kPolyethylene}) {
    EXPECT_EQ(MaterialAlbedo(m, 7, p), MaterialAlbedo(m, 7, p));
    // Some point of a small patch differs with the seed.
    double differs = 0.0;
    for (int i = 0; i < 100; ++i) {
      const Eigen::Vector2d q = p + Eigen::Vector2d(0.37 * i, 0.11 * i);
      differs = std::max(differs, (MaterialAlbedo(m, 7, q) - MaterialAlbedo(m, 8, q)).norm());
    }
    EXPECT_GT(differs, 1e-3) << static_cast<int>(m);
  }
}

TEST(Material, AlbedosArePlausible) {
  const cv::Scalar concrete = Mean(Raster(Material::kConcrete, 3));
  const double grey = (concrete[0] + concrete[1] + concrete[2]) / 3.0;
  EXPECT_GT(grey, 0.38);
  EXPECT_LT(grey, 0.52);
  const cv::Scalar clay = Mean(Raster(Material::kVitrifiedClay, 3));
  EXPECT_GT(clay[0], 1.4 * clay[1]);  // reddish brown: R > G > B
  EXPECT_GT(clay[1], 1.4 * clay[2]);
  EXPECT_NEAR(clay[0], 0.33, 0.05);
  const cv::Mat3f plastic = Raster(Material::kPlastic, 3);
  cv::Scalar mean, stddev;
  cv::meanStdDev(plastic.reshape(1, static_cast<int>(plastic.total())).col(0), mean, stddev);
  EXPECT_NEAR(mean[0], 0.62, 0.02);
  EXPECT_LT(stddev[0], 0.02 * 0.62);  // nearly uniform
  // Black polyethylene: the same structure in carbon black, a twelfth as bright in the red.
  const cv::Scalar black = Mean(Raster(Material::kPolyethylene, 3));
  EXPECT_NEAR(black[0], 0.045, 0.003);
  EXPECT_NEAR(black[2], 0.05, 0.003);
}

TEST(Material, ConcreteAndClayHaveFineStructurePlasticHardlyAny) {
  const cv::Mat3f concrete = Raster(Material::kConcrete, 5);
  const cv::Mat3f clay = Raster(Material::kVitrifiedClay, 5);
  const cv::Mat3f plastic = Raster(Material::kPlastic, 5);
  const int sift_concrete = SiftKeypoints(concrete), sift_clay = SiftKeypoints(clay);
  const int sift_plastic = SiftKeypoints(plastic);
  RecordProperty("sift_concrete", sift_concrete);
  RecordProperty("sift_clay", sift_clay);
  RecordProperty("sift_plastic", sift_plastic);
  // 3072 mm²; a full-size image sees ~15 times more wall (docs/simulator.md: thousands).
  EXPECT_GT(sift_concrete, 300);
  EXPECT_GT(sift_clay, 150);
  EXPECT_LT(sift_plastic, 20);
  EXPECT_GT(EdgeDensity(concrete), 0.02);
  EXPECT_GT(EdgeDensity(clay), 0.002);
  EXPECT_LT(EdgeDensity(plastic), 1e-3);
}

}  // namespace
}  // namespace sewer3d
