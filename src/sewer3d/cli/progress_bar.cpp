#include "sewer3d/cli/progress_bar.hpp"

#include <unistd.h>

#include <cstdio>

namespace sewer3d::cli {

ProgressBar::ProgressBar(bool quiet) : quiet_(quiet), terminal_(isatty(fileno(stderr)) != 0) {}

ProgressBar::~ProgressBar() {
  if (line_open_) std::fprintf(stderr, "\n");
}

void ProgressBar::Update(const std::string& label, int done, int total, const char* unit) {
  if (quiet_ || total <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (label != label_) {
    label_ = label;
    start_ = now;
  }
  const double seconds = std::chrono::duration<double>(now - start_).count();
  if (!terminal_) {  // a log gets whole lines only
    if (done == total)
      std::fprintf(stderr, "%s: %d %s in %.1f s\n", label.c_str(), total, unit, seconds);
    return;
  }
  const int width = 30, filled = width * done / total;
  const double eta = done > 0 ? seconds / done * (total - done) : 0.0;
  std::fprintf(stderr, "\r%s: [%s%s] %d/%d %s  %.0f s  ETA %.0f s ", label.c_str(),
               std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), done,
               total, unit, seconds, eta);
  line_open_ = done != total;
  if (!line_open_) std::fprintf(stderr, "\n");
}

}  // namespace sewer3d::cli
