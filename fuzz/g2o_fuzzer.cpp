// g2o pose graphs (io/g2o_io ReadG2o; it takes a path).
#include "fuzz_input.hpp"
#include "sewer3d/io/g2o_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = sewer3d::fuzz::InputFile(data, size, ".g2o");
  sewer3d::fuzz::Refusing([&] { sewer3d::ReadG2o(path); });
  return 0;
}
