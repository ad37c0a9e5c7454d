#include "sewer3d/pipeline/acquisition_images.hpp"

#include <fmt/core.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"

namespace sewer3d {
namespace {

void CheckSize(const std::filesystem::path& file, const cv::Mat& image,
               const CameraIntrinsics& camera, int module) {
  if (image.cols != camera.width || image.rows != camera.height) {
    throw FileError(file, fmt::format("image is {}x{} but module m{}'s camera is {}x{}", image.cols,
                                      image.rows, module, camera.width, camera.height));
  }
}

const CameraIntrinsics& CameraOf(const CaptureRun& run, const Acquisition& a) {
  return run.rig.modules.at(a.module).module.camera;
}

std::filesystem::path ExistingImageFile(const CaptureRun& run, const Acquisition& a,
                                        ImageKind kind) {
  std::filesystem::path file = AcquisitionImageFile(run, a, kind);
  if (a.Image(kind) < 0)
    throw FileError(file, std::string("no ") + ImageKindName(kind) + " image in acquisitions.csv");
  if (run.images[a.Image(kind)].missing) {
    std::error_code ec;
    const bool exists = std::filesystem::exists(file, ec);
    if (ec && ec != std::errc::no_such_file_or_directory) {  // a link loop, no permission
      throw FileError(file, "listed in acquisitions.csv but cannot be reached: " + ec.message());
    }
    throw FileError(file, exists ? "listed in acquisitions.csv but not a regular file (a folder, "
                                   "FIFO or device)"
                                 : "listed in acquisitions.csv but missing");
  }
  return file;
}

// The first of `images` (indices into the run's) that decodes, trying at most kTries: its
// size, channels and file; nullopt when none does.
struct ReadableImage {
  cv::Size size;
  int channels = 0;
  std::string file;
};
constexpr int kTries = 3;
template <typename It>
std::optional<ReadableImage> FirstReadable(const CaptureRun& run, It begin, It end) {
  int tries = 0;
  for (It it = begin; it != end && tries < kTries; ++it) {
    const RunImage& image = run.images[*it];
    if (image.missing) continue;
    ++tries;
    try {
      const cv::Mat decoded = ReadImage(run.folder / image.file, cv::IMREAD_UNCHANGED);
      return ReadableImage{decoded.size(), decoded.channels(), image.file};
    } catch (const FileError&) {  // a bad image: its acquisition fails on its own
    }
  }
  return std::nullopt;
}

// run.json's color_filter against the first texture image that decodes: a raw mosaic has one
// channel, a colour image three or four.
void CheckColorFilterMatchesImages(const CaptureRun& run) {
  std::vector<int> textures;
  for (size_t i = 0; i < run.images.size(); ++i)
    if (run.images[i].kind != ImageKind::kPattern) textures.push_back(static_cast<int>(i));
  const auto first = FirstReadable(run, textures.begin(), textures.end());
  if (!first) return;
  const bool mosaic = run.info.color_filter != "none";
  if (mosaic == (first->channels == 1)) return;
  throw FileError(
      run.folder / "run.json",
      fmt::format("color_filter \"{}\" ({}), but the texture images have {} "
                  "channel{} ({}): run.json does not match the images",
                  run.info.color_filter, mosaic ? "raw one-channel mosaics" : "colour images",
                  first->channels, first->channels == 1 ? "" : "s", first->file));
}

}  // namespace

void CheckRigMatchesImages(const CaptureRun& run) {
  for (size_t k = 0; k < run.rig.modules.size(); ++k) {
    std::vector<int> images;
    for (size_t i = 0; i < run.images.size(); ++i)
      if (run.images[i].module == static_cast<int>(k)) images.push_back(static_cast<int>(i));
    const auto first = FirstReadable(run, images.begin(), images.end());
    if (!first) continue;
    const auto last = FirstReadable(run, images.rbegin(), images.rend());
    const CameraIntrinsics& camera = run.rig.modules[k].module.camera;
    const cv::Size expected(camera.width, camera.height);
    if (first->size == expected || (last && last->size == expected)) continue;
    std::string files = first->file;
    if (last && last->file != first->file) files += " and " + last->file;
    throw FileError(run.folder / "rig.json",
                    fmt::format("modules[{}].module.camera: {}x{} px, but module m{}'s images are "
                                "{}x{} ({}): the rig does not match the images",
                                k, camera.width, camera.height, k, first->size.width,
                                first->size.height, files));
  }
  CheckColorFilterMatchesImages(run);
}

std::filesystem::path AcquisitionImageFile(const CaptureRun& run, const Acquisition& a,
                                           ImageKind kind) {
  const int i = a.Image(kind);
  if (i >= 0) return run.folder / run.images[i].file;
  return run.folder / "images" / (ImageStem(a.module, a.counter, kind) + ".png");
}

cv::Mat ReadPatternImage(const CaptureRun& run, const Acquisition& a) {
  const std::filesystem::path file = ExistingImageFile(run, a, ImageKind::kPattern);
  cv::Mat image = ReadGreyImage(file);
  CheckSize(file, image, CameraOf(run, a), a.module);
  return image;
}

cv::Mat3b ReadTextureImage(const CaptureRun& run, const Acquisition& a, ImageKind kind) {
  const std::filesystem::path file = ExistingImageFile(run, a, kind);
  if (run.info.color_filter == "none") {
    cv::Mat image = ReadImage(file, cv::IMREAD_UNCHANGED, kMaxCameraPixels);
    if (image.channels() == 1) {
      throw FileError(file,
                      "a one-channel image, but run.json's color_filter is \"none\" "
                      "(colour images); a raw Bayer mosaic needs \"RGGB\"");
    }
    CheckSize(file, image, CameraOf(run, a), a.module);
    if (image.channels() == 4) cv::cvtColor(image, image, cv::COLOR_BGRA2BGR);
    if (image.depth() == CV_16U) image.convertTo(image, CV_8U, 1.0 / 257.0);
    if (image.type() != CV_8UC3) throw FileError(file, "expected an 8- or 16-bit colour image");
    return image;
  }
  cv::Mat raw = ReadImage(file, cv::IMREAD_UNCHANGED, kMaxCameraPixels);
  if (raw.channels() != 1)
    throw FileError(file,
                    "run.json says the camera has a colour filter array, but the image "
                    "has " +
                        std::to_string(raw.channels()) + " channels, not a raw mosaic");
  CheckSize(file, raw, CameraOf(run, a), a.module);
  // A 16-bit raw uses the full 16-bit range (docs/formats.md); the texture path works in 8 bits.
  if (raw.depth() == CV_16U) raw.convertTo(raw, CV_8U, 255.0 / 65535.0);
  cv::Mat3b bgr;
  // RGGB (red at row 0, column 0) is OpenCV's "BayerBG" (named from the second row's second
  // and third pixels); edge-aware interpolation keeps the wall's fine texture.
  cv::cvtColor(raw, bgr, cv::COLOR_BayerBG2BGR_EA);
  return bgr;
}

cv::Mat3f ReadLinearTexture(const CaptureRun& run, const Acquisition& a, ImageKind kind) {
  cv::Mat3f linear;
  ReadTextureImage(run, a, kind).convertTo(linear, CV_32F, 1.0 / 255);
  return linear;
}

}  // namespace sewer3d
