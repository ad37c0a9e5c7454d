// Pattern matrix images, PNG above all (io/image_io ReadPatternMatrix: header size, the whole
// PNG check of io/png_check, then OpenCV's decoder, then the matrix; it takes a path).
// The harness writes every complete chunk's CRC afresh, so that mutations reach the header,
// palette and image-data checks instead of stopping at the first CRC mismatch.
#include <zlib.h>

#include <vector>

#include "fuzz_input.hpp"
#include "sewer3d/io/image_io.hpp"

namespace {

std::vector<std::uint8_t> WithFreshCrcs(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> b(data, data + size);
  std::size_t at = 8;
  while (at + 12 <= b.size()) {
    const std::uint64_t length = (std::uint64_t{b[at]} << 24) | (std::uint64_t{b[at + 1]} << 16) |
                                 (std::uint64_t{b[at + 2]} << 8) | b[at + 3];
    if (length > b.size() - at - 12) break;
    const auto crc = crc32(0, b.data() + at + 4, static_cast<uInt>(4 + length));
    for (int k = 0; k < 4; ++k)
      b[at + 8 + length + k] = static_cast<std::uint8_t>(crc >> (24 - 8 * k));
    at += 12 + length;
  }
  return b;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::uint8_t> bytes = WithFreshCrcs(data, size);
  const auto path = sewer3d::fuzz::InputFile(bytes.data(), bytes.size(), ".png");
  sewer3d::fuzz::Refusing([&] { sewer3d::ReadPatternMatrix(path); });
  return 0;
}
