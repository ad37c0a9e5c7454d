#include "sewer3d/cli/demo_summary.hpp"

#include <fmt/core.h>
#include <sys/resource.h>

#include <algorithm>
#include <utility>

namespace sewer3d::cli {

double PeakMemoryGb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1e6;  // kB on Linux
}

void PrintLookAt(const std::filesystem::path& dir, const std::filesystem::path& html) {
  constexpr std::pair<const char*, const char*> kLookAt[] = {
      {"ws/model/preview.png", "the unrolled pipe: texture over displacement"},
      {"ws/model/mesh.glb", "the displaced 3D model (any glTF viewer)"},
      {"ws/model/mesh.obj", "the textured cylinder (MeshLab, Blender)"},
      {"ws/inspection/observations.csv", "EN 13508-2 observations (crops/: their maps)"},
      {"ws/evaluation/model/error_map.png", "the model against the true wall"},
      {"run/truth/overview.png", "the unrolled pipe and every image's footprint"},
      {"ws/rgbd/m0/000000_color.png", "corrected colour at the pattern instant"},
      {"ws/rgbd/m0/000000_depth_preview.png", "its depth map"},
      {"ws/registration/graph.png", "the pose graph"},
      {"ws/evaluation/rgbd/colour_montage.png", "captured | corrected | true albedo"},
      {"ws/evaluation/*/evaluation.json", "the figures above"},
      {"ws/workspace.json", "options, stages done, seconds"}};
  size_t width = html.string().size();
  for (const auto& item : kLookAt) width = std::max(width, (dir / item.first).string().size());
  fmt::print("look at:\n  {:<{}}  the inspection report (any browser, offline)\n", html.string(),
             width);
  for (const auto& [path, what] : kLookAt)
    fmt::print("  {:<{}}  {}\n", (dir / path).string(), width, what);
}

}  // namespace sewer3d::cli
