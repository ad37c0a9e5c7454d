// The rig checked against the images (a rig whose camera size is not the images' is refused
// naming rig.json; one odd image is left to its acquisition) and a missing image's message.

#include "sewer3d/pipeline/acquisition_images.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

class RigAgainstImages : public ::testing::Test {
 protected:
  void SetUp() override {
    run_.folder = fs::temp_directory_path() / "sewer3d_acquisition_images_test";
    fs::remove_all(run_.folder);
    for (int k = 0; k < 2; ++k) {
      std::string name = "m";
      name += std::to_string(k);  // not "m" + …: GCC 12 warns falsely (-Wrestrict) there
      run_.rig.modules.push_back({name, 12.0, testing::SmallDefaultModule(), {}});
    }
    width_ = run_.rig.modules[0].module.camera.width;
    height_ = run_.rig.modules[0].module.camera.height;
  }
  void TearDown() override { fs::remove_all(run_.folder); }

  // Lists an image of module k, counter c (a pattern image), written at width x height.
  void AddImage(int k, int c, int width, int height) {
    RunImage image{k, c, ImageKind::kPattern, 0.1 * c, 2.0, ImageStem(k, c, ImageKind::kPattern)};
    image.file = "images/" + image.file + ".png";
    WriteImage(run_.folder / image.file, cv::Mat1b(height, width, 128));
    run_.images.push_back(image);
  }

  std::string ErrorOf() {
    try {
      CheckRigMatchesImages(run_);
    } catch (const FileError& e) {
      return e.what();
    }
    return "";
  }

  CaptureRun run_;
  int width_ = 0, height_ = 0;
};

TEST_F(RigAgainstImages, RefusesACameraSizeNoImageHas) {
  for (int c = 0; c < 3; ++c) {
    AddImage(0, c, width_, height_);
    AddImage(1, c, width_ - 8, height_);
  }
  const std::string error = ErrorOf();
  EXPECT_NE(error.find((run_.folder / "rig.json").string() +
                       ": modules[1].module.camera: " + std::to_string(width_) + "x" +
                       std::to_string(height_) + " px, but module m1's images are " +
                       std::to_string(width_ - 8) + "x" + std::to_string(height_)),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("images/m1/000000_pattern.png and images/m1/000002_pattern.png"),
            std::string::npos)
      << error;
}

TEST_F(RigAgainstImages, LeavesOneOddOrMissingImageToItsAcquisition) {
  AddImage(0, 0, width_ - 8, height_);  // odd: its acquisition fails on its own
  AddImage(0, 1, width_, height_);
  AddImage(1, 0, width_, height_);
  AddImage(1, 1, width_, height_);
  fs::remove(run_.folder / run_.images[2].file);
  run_.images[2].missing = true;
  EXPECT_EQ(ErrorOf(), "");
  Acquisition a;
  a.module = 1;
  a.image[static_cast<int>(ImageKind::kPattern)] = 2;
  try {
    ReadPatternImage(run_, a);
    FAIL() << "a missing image was read";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("000000_pattern.png: listed in acquisitions.csv but "
                                         "missing"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sewer3d
