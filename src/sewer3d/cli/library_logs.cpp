#include "sewer3d/cli/library_logs.hpp"

#include <glog/logging.h>

#include <cstdlib>
#include <opencv2/core/utils/logger.hpp>

namespace sewer3d::cli {

void QuietLibraryLogs() {
  if (std::getenv("SEWER3D_LIBRARY_LOGS") != nullptr) return;
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  FLAGS_minloglevel = google::GLOG_FATAL;
  FLAGS_stderrthreshold = google::GLOG_FATAL;
}

}  // namespace sewer3d::cli
