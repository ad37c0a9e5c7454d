#include "sewer3d/cli/library_logs.hpp"

#include <glog/logging.h>

#include <cstdlib>
#include <iostream>
#include <opencv2/core/utils/logger.hpp>

namespace sewer3d::cli {

void QuietLibraryLogs() {
  if (std::getenv("SEWER3D_LIBRARY_LOGS") != nullptr) return;
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  FLAGS_minloglevel = google::GLOG_FATAL;
  FLAGS_stderrthreshold = google::GLOG_FATAL;
  // OpenCV's decoders write a caught codec error to std::cerr before returning an empty image
  // (a truncated TIFF strip); sewer3d itself writes stderr through C stdio only, so the C++
  // error streams are muted: a failed stream writes nothing.
  std::cerr.setstate(std::ios::badbit);
  std::clog.setstate(std::ios::badbit);
}

}  // namespace sewer3d::cli
