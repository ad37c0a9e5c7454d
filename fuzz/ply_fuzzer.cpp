// PLY point clouds, ASCII and binary (io/ply_io ReadPlyPoints; it takes a path).
#include "fuzz_input.hpp"
#include "sewer3d/io/ply_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = sewer3d::fuzz::InputFile(data, size, ".ply");
  sewer3d::fuzz::Refusing([&] { sewer3d::ReadPlyPoints(path); });
  return 0;
}
