#pragma once
/// \file
/// The one progress display of long commands: `label: [#####.....] done/total unit  T s  ETA
/// E s` on stderr, redrawn in place, a new line when a phase ends; silent when quiet.

#include <chrono>
#include <string>

namespace sewer3d::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool quiet) : quiet_(quiet) {}
  /// Draws `done` of `total` for phase `label`; a new label restarts the phase clock.
  void Update(const std::string& label, int done, int total, const char* unit);

 private:
  bool quiet_;
  std::string label_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace sewer3d::cli
