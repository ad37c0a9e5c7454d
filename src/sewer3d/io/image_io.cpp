#include "sewer3d/io/image_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/input_file.hpp"
#include "sewer3d/io/png_check.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
void WriteImage(const std::filesystem::path& path, const cv::Mat& image) {
  // Encoded in memory and written by us: a full disk is then one FileError naming `path`,
  // without libpng's or libtiff's own lines on stderr or the temporary file's name.
  std::vector<std::uint8_t> bytes;
  try {
    if (!cv::imencode(path.extension().string(), image, bytes))
      throw FileError(path, "cannot encode the image");
  } catch (const cv::Exception& e) {
    throw FileError(path, std::string("cannot write image: ") + e.err);
  }
  WriteTextFile(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

cv::Mat ReadImage(const std::filesystem::path& path, int imread_flags, std::uint64_t max_pixels) {
  const std::vector<std::uint8_t> bytes = ReadFileBytes(path);
  if (bytes.empty()) throw FileError(path, "empty file, not an image");
  // Only PNG, TIFF and JPEG reach OpenCV: its other decoders (GDCM among them) may abort.
  const auto header = ImageHeaderSize(bytes);
  if (!header) {
    const std::string format = ImageFormat(bytes);
    throw FileError(
        path, format.empty() ? "not a PNG, TIFF or JPEG image"
                             : "cannot decode image: a truncated or corrupt " + format + " header");
  }
  if (const auto& size = header) {
    if (size->width == 0 || size->height == 0 || size->width * size->height > max_pixels) {
      throw FileError(path, fmt::format("the header declares {} x {} pixels; at most {} are read",
                                        size->width, size->height, max_pixels));
    }
  }
  PngCheck check;
  if (ImageFormat(bytes) == "PNG") {
    check = CheckPng(bytes);
    if (!check.problem.empty()) throw FileError(path, "cannot decode image: " + check.problem);
  }
  cv::Mat image;
  try {
    image = cv::imdecode(check.essential.empty() ? bytes : check.essential, imread_flags);
  } catch (const cv::Exception& e) {
    throw FileError(path, std::string("cannot decode image: ") + e.err);
  }
  if (image.empty()) {
    // Decodable as it is (a float TIFF, a depth map), only not in the way asked for?
    cv::Mat as_is;
    try {
      as_is = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception&) {  // undecodable either way: the message below
    }
    if (!as_is.empty() && as_is.depth() != CV_8U && as_is.depth() != CV_16U) {
      throw FileError(path, fmt::format("expected an 8-bit or 16-bit image, got {} samples "
                                        "(a depth map?)",
                                        as_is.depth() == CV_32F   ? "32-bit float"
                                        : as_is.depth() == CV_64F ? "64-bit float"
                                                                  : "other"));
    }
    throw FileError(path, "cannot decode image (not an image, or truncated)");
  }
  return image;
}

cv::Mat ReadGreyImage(const std::filesystem::path& path) {
  cv::Mat image = ReadImage(path, cv::IMREAD_ANYDEPTH | cv::IMREAD_GRAYSCALE, kMaxCameraPixels);
  if (image.depth() != CV_8U && image.depth() != CV_16U) {
    throw FileError(path, "expected an 8-bit or 16-bit image");
  }
  return image;
}

std::pair<double, double> WriteDepthPreview(const std::filesystem::path& path,
                                            const cv::Mat1f& depth_mm) {
  double lo = 1e300, hi = -1e300;
  for (float z : depth_mm) {
    if (std::isfinite(z)) lo = std::min<double>(lo, z), hi = std::max<double>(hi, z);
  }
  cv::Mat1b scaled(depth_mm.size(), 0);
  for (int v = 0; v < scaled.rows; ++v) {
    for (int u = 0; u < scaled.cols; ++u) {
      const float z = depth_mm(v, u);
      if (std::isfinite(z) && hi > lo)
        scaled(v, u) = cv::saturate_cast<std::uint8_t>(1 + 254.0 * (hi - z) / (hi - lo));
    }
  }
  cv::Mat colour;
  cv::applyColorMap(scaled, colour, cv::COLORMAP_TURBO);
  colour.setTo(cv::Scalar::all(0), scaled == 0);
  WriteImage(path, colour);
  return {lo, hi};
}

BinaryArray ReadPatternMatrix(const std::filesystem::path& path) {
  cv::Mat image = ReadImage(path, cv::IMREAD_UNCHANGED, std::uint64_t{kMaxPatternElements});
  if (image.channels() > 1) {
    std::vector<cv::Mat> channels;
    cv::split(image, channels);
    // A spot is any colour but black; alpha (grey + alpha, colour + alpha) is not a colour: an
    // opaque export has 255 there everywhere.
    const size_t colours =
        channels.size() == 2 || channels.size() == 4 ? channels.size() - 1 : channels.size();
    cv::Mat any = channels[0] != 0;
    for (size_t i = 1; i < colours; ++i) any |= channels[i] != 0;
    image = any;
  }
  BinaryArray array(image.rows, image.cols);
  cv::Mat spots = image != 0;
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) array.set(r, c, spots.at<std::uint8_t>(r, c) ? 1 : 0);
  }
  return array;
}

void WritePatternMatrix(const std::filesystem::path& path, const BinaryArray& array) {
  if (path.extension() != ".png") throw FileError(path, "a pattern matrix is written as PNG only");
  cv::Mat1b image(array.rows, array.cols);
  for (int r = 0; r < array.rows; ++r) {
    for (int c = 0; c < array.cols; ++c) image(r, c) = array.at(r, c) ? 255 : 0;
  }
  WriteImage(path, image);
}

void WritePatternPreview(const std::filesystem::path& path, const BinaryArray& array, int scale,
                         int window) {
  cv::Mat3b image(array.rows * scale, array.cols * scale, cv::Vec3b(20, 20, 20));
  for (int r = 0; r < array.rows; ++r) {
    for (int c = 0; c < array.cols; ++c) {
      if (!array.at(r, c)) continue;
      cv::circle(image, {c * scale + scale / 2, r * scale + scale / 2}, std::max(1, scale / 3),
                 cv::Scalar(255, 255, 255), cv::FILLED, cv::LINE_AA);
    }
  }
  for (int c = 0; c <= array.cols; c += window) {
    cv::line(image, {c * scale, 0}, {c * scale, image.rows}, cv::Scalar(0, 120, 255), 1);
  }
  WriteImage(path, image);
}

}  // namespace sewer3d
