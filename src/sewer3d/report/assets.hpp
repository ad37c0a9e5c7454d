#pragma once
/// \file
/// The report's own scripts and style sheet, embedded into the binary at build time
/// (embed_assets.cmake): report.js (map views, readouts), report.css, and the 3D viewer
/// (viewer.js bundled with three.js by esbuild, viewer.cmake).

#include <string_view>

namespace sewer3d {

struct ReportAssets {
  std::string_view report_js;
  std::string_view report_css;
  /// The viewer's classic script with three.js inside; empty when npm was not available when
  /// the build was configured (the report then says the viewer is unavailable).
  std::string_view viewer_js;
};

const ReportAssets& EmbeddedReportAssets();

}  // namespace sewer3d
