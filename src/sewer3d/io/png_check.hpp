#pragma once
/// \file
/// A PNG checked in full before OpenCV decodes it, so that libpng never meets a broken file
/// (it would print its own lines on stderr) and a broken file gets one clear reason.

#include <cstdint>
#include <string>
#include <vector>

namespace sewer3d {

struct PngCheck {
  /// What is wrong ("" when nothing): the chunk structure (a chunk past the end, a CRC error, no
  /// IHDR first, no IEND, IDAT chunks not in one run, an unknown critical chunk), the header
  /// (colour type, bit depth, compression, filter and interlace methods), PLTE and tRNS against
  /// the colour type, and the image data: a valid zlib stream that inflates to exactly the
  /// rows the header declares (Adam7 passes included), each row with a filter type 0..4.
  std::string problem;
  /// The file with only the chunks that define the pixels (IHDR, PLTE, tRNS, IDAT, IEND); empty
  /// when the file holds no other chunk (decode it as it is).
  std::vector<std::uint8_t> essential;
};

/// Checks a whole PNG file (signature included).
PngCheck CheckPng(const std::vector<std::uint8_t>& bytes);

}  // namespace sewer3d
