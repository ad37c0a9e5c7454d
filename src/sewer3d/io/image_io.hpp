#pragma once
/// \file
/// Reading and writing images and pattern matrices. Errors are FileError.

#include <cstdint>
#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <utility>

#include "sewer3d/pattern/binary_array.hpp"

namespace sewer3d {

/// Writes any image OpenCV can encode (format from the extension); creates parent folders.
void WriteImage(const std::filesystem::path& path, const cv::Mat& image);

/// Most pixels ReadImage decodes by default (256 M: a 100 m model's texture in tiles is far
/// below) and of a camera image (64 M). A pattern matrix is limited to kMaxPatternElements.
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t{1} << 28;
inline constexpr std::uint64_t kMaxCameraPixels = std::uint64_t{1} << 26;

/// Reads an image file (OpenCV imread flags), with a clear error for missing, truncated or
/// undecodable files, and for a header declaring more than max_pixels (checked before decoding).
cv::Mat ReadImage(const std::filesystem::path& path, int imread_flags,
                  std::uint64_t max_pixels = kMaxImagePixels);

/// Reads a camera image as one grey channel, 8 or 16 bits (colour is converted).
cv::Mat ReadGreyImage(const std::filesystem::path& path);

/// Writes a colour-mapped picture of a depth map (near red, far blue, NaN black); returns the
/// depth range it mapped (min, max; min > max when no depth is finite).
std::pair<double, double> WriteDepthPreview(const std::filesystem::path& path,
                                            const cv::Mat1f& depth_mm);

/// Reads a pattern matrix PNG (one pixel per element, non-zero = spot, DESIGN.md contract).
/// Colour images count a pixel as a spot when any channel is non-zero.
BinaryArray ReadPatternMatrix(const std::filesystem::path& path);

/// Writes a matrix PNG: 8-bit grey, 255 = spot, 0 = no spot. Creates parent folders.
void WritePatternMatrix(const std::filesystem::path& path, const BinaryArray& array);

/// Writes an enlarged, human-viewable picture of the matrix (each element scale x scale px,
/// spots as white disks, grid lines every window elements).
void WritePatternPreview(const std::filesystem::path& path, const BinaryArray& array, int scale,
                         int window);

}  // namespace sewer3d
