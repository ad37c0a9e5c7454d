// module.json text (io/module_io ParseModule, which reads no other file).
#include <string>

#include "fuzz_input.hpp"
#include "sewer3d/io/module_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  sewer3d::fuzz::Refusing([&] { sewer3d::ParseModule(text, "fuzz/module.json"); });
  return 0;
}
