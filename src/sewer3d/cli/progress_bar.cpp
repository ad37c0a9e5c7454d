#include "sewer3d/cli/progress_bar.hpp"

#include <cstdio>

namespace sewer3d::cli {

void ProgressBar::Update(const std::string& label, int done, int total, const char* unit) {
  if (quiet_ || total <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (label != label_) {
    label_ = label;
    start_ = now;
  }
  const double seconds = std::chrono::duration<double>(now - start_).count();
  const int width = 30, filled = width * done / total;
  const double eta = done > 0 ? seconds / done * (total - done) : 0.0;
  std::fprintf(stderr, "\r%s: [%s%s] %d/%d %s  %.0f s  ETA %.0f s ", label.c_str(),
               std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), done,
               total, unit, seconds, eta);
  if (done == total) std::fprintf(stderr, "\n");
}

}  // namespace sewer3d::cli
