// The index files of a capture run (io/run_io): the first byte picks the reader (0 run.json,
// 1 acquisitions.csv, 2 odometry.csv), the rest is the file.
#include "fuzz_input.hpp"
#include "sewer3d/io/run_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int reader = data[0] % 3;
  const auto path = sewer3d::fuzz::InputFile(data + 1, size - 1, ".index");
  sewer3d::fuzz::Refusing([&] {
    if (reader == 0)
      sewer3d::ReadRunInfo(path);
    else if (reader == 1)
      sewer3d::ReadIndex(path);
    else
      sewer3d::ReadOdometry(path);
  });
  return 0;
}
