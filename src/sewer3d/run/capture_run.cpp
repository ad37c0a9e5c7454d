#include "sewer3d/run/capture_run.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <utility>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

const char* ImageKindName(ImageKind kind) {
  switch (kind) {
    case ImageKind::kTextureBefore:
      return "texture_before";
    case ImageKind::kPattern:
      return "pattern";
    case ImageKind::kTextureAfter:
      return "texture_after";
  }
  return "?";
}

std::optional<ImageKind> ParseImageKind(std::string_view name) {
  for (const ImageKind k : kImageKinds) {
    if (name == ImageKindName(k)) return k;
  }
  return std::nullopt;
}

std::string ImageStem(int module, int counter, ImageKind kind) {
  char stem[64];
  std::snprintf(stem, sizeof stem, "m%d/%06d_%s", module, counter, ImageKindName(kind));
  return stem;
}

std::vector<Acquisition> GroupAcquisitions(const std::vector<RunImage>& images) {
  std::map<std::pair<int, int>, Acquisition> by_key;
  for (size_t i = 0; i < images.size(); ++i) {
    const RunImage& im = images[i];
    Acquisition& a = by_key[{im.module, im.counter}];
    a.module = im.module;
    a.counter = im.counter;
    int& slot = a.image[static_cast<int>(im.kind)];
    SEWER3D_VALIDATE(slot < 0, "images",
                     "module " << im.module << " counter " << im.counter << " has two "
                               << ImageKindName(im.kind) << " images");
    slot = static_cast<int>(i);
  }
  std::vector<Acquisition> out;
  out.reserve(by_key.size());
  for (auto& [key, a] : by_key) out.push_back(a);
  return out;
}

}  // namespace sewer3d
