#pragma once
/// \file
/// The tiny simulated run the pipeline's stage tests share (PresetScenario("tiny") with the
/// 648 × 486 module, truth depth of the pattern images): 36 images, about 40 s of CPU to
/// render. CTest renders it once (test `pipeline/tiny_run_fixture_sim`, a CTest fixture) into
/// the folder SEWER3D_TINY_RUN names, and each test copies it (some change its images); run by
/// hand without that variable, a test renders its own.

#include <cstdlib>
#include <filesystem>

#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/simio/simulate_run.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d::testing {

/// Renders the tiny run into `folder` (replaced).
inline void SimulateTinyRun(const std::filesystem::path& folder) {
  std::filesystem::remove_all(folder);
  Scenario s = PresetScenario("tiny");
  s.truth_depth = TruthDepth::kPattern;
  SimulateRun(s, SmallDefaultModule(s.camera_width), DefaultPatternArray(), folder, {});
}

/// The shared run's folder, when CTest's fixture wrote one (its run.json marks it complete).
inline std::filesystem::path SharedTinyRun() {
  const char* shared = std::getenv("SEWER3D_TINY_RUN");
  if (shared == nullptr || *shared == '\0') return {};
  const std::filesystem::path folder(shared);
  return std::filesystem::exists(folder / "run.json") ? folder : std::filesystem::path{};
}

/// The tiny run at `folder` (replaced): a copy of the shared one, or rendered here.
inline void MakeTinyRun(const std::filesystem::path& folder) {
  const std::filesystem::path shared = SharedTinyRun();
  if (shared.empty()) {
    SimulateTinyRun(folder);
    return;
  }
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder.parent_path());
  std::filesystem::copy(shared, folder, std::filesystem::copy_options::recursive);
}

}  // namespace sewer3d::testing
