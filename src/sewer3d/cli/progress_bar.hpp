#pragma once
/// \file
/// The one progress display of long commands: on a terminal, `label: [#####.....] done/total
/// unit  T s  ETA E s` on stderr, redrawn in place, a new line when a phase ends (or the bar
/// goes, so that an error starts its own line); elsewhere (a log file, a pipe) one line per
/// finished phase; silent when quiet.

#include <chrono>
#include <string>

namespace sewer3d::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool quiet);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  /// Draws `done` of `total` for phase `label`; a new label restarts the phase clock.
  void Update(const std::string& label, int done, int total, const char* unit);

 private:
  bool quiet_;
  bool terminal_;
  bool line_open_ = false;  ///< a bar is drawn and its line not ended
  std::string label_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace sewer3d::cli
