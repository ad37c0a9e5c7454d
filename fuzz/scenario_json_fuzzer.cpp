// Scenario JSON text (simio ParseScenario, with the scenario's own Check()).
#include <string>

#include "fuzz_input.hpp"
#include "sewer3d/simio/scenario_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  sewer3d::fuzz::Refusing([&] { sewer3d::ParseScenario(text, "fuzz/scenario.json"); });
  return 0;
}
