// Writes the tiny run the stage tests share (tiny_run_sim_test.hpp) into SEWER3D_TINY_RUN —
// CTest runs it before them as a fixture — or, without that variable, into a temporary folder;
// either way checks that it is a whole capture run of six modules.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "sewer3d/io/run_io.hpp"
#include "sewer3d/pipeline/tiny_run_sim_test.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

TEST(TinyRunFixture, IsAWholeRunOfSixModules) {
  const char* shared = std::getenv("SEWER3D_TINY_RUN");
  const bool keep = shared != nullptr && *shared != '\0';
  const fs::path folder = keep ? fs::path(shared) : fs::temp_directory_path() / "sewer3d_tiny_run";
  // Rendered beside the folder and moved in at the end: run.json marks a finished one.
  const fs::path partial = folder.string() + ".partial";
  testing::SimulateTinyRun(partial);
  fs::remove_all(folder);
  fs::rename(partial, folder);
  const CaptureRun run = LoadRun(folder);
  EXPECT_EQ(run.rig.modules.size(), 6u);
  EXPECT_EQ(run.images.size(), 36u);  // two instants of six modules, three images each
  if (keep) {
    EXPECT_EQ(testing::SharedTinyRun(), folder);
  } else {
    fs::remove_all(folder);
  }
}

}  // namespace
}  // namespace sewer3d
