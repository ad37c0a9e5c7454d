// Pattern matrix images, PNG above all (io/image_io ReadPatternMatrix: signature and IEND
// checks, then OpenCV's decoder, then the matrix; it takes a path).
#include "fuzz_input.hpp"
#include "sewer3d/io/image_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = sewer3d::fuzz::InputFile(data, size, ".png");
  sewer3d::fuzz::Refusing([&] { sewer3d::ReadPatternMatrix(path); });
  return 0;
}
