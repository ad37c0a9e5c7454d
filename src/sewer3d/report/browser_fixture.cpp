// The browser test's workspace (docs/report.md): a 200 mm DN300 model at 1 mm with a known bump
// (test_model.hpp), written through io, and its report written through WriteReport with a
// profile, one observation and an evaluation. Writes WS/expected.json with the bump's station,
// clock and radius for browser_test.mjs.
//
// usage: report_browser_fixture WS

#include <fmt/core.h>

#include <cstdio>
#include <exception>
#include <filesystem>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/model_io.hpp"
#include "sewer3d/io/workspace_io.hpp"
#include "sewer3d/report/report.hpp"
#include "sewer3d/report/test_model.hpp"
#include "sewer3d/report/workspace_inputs.hpp"

int main(int argc, char** argv) {
  using namespace sewer3d;
  if (argc != 2) {
    std::fprintf(stderr, "usage: report_browser_fixture WS\n");
    return 2;
  }
  try {
    const std::filesystem::path ws = argv[1];
    const double radius_mm = 150.0;
    const testing_report::KnownBump bump;
    const MapGrid grid = MakeMapGrid(0.0, 200.0, radius_mm, 1.0);
    const Centreline centreline = testing_report::StraightCentreline(0.0, 200.0, radius_mm);
    WritePipeModel(ws / "model", centreline, testing_report::BumpMaps(grid, radius_mm, bump), 0.0,
                   ModelFileOptions{});
    WorkspaceRecord record;
    record.run = (ws / "run").string();
    record.stages["model"].seconds = 1.5;
    record.stages["model"].done = true;
    WriteWorkspaceRecord(ws / "workspace.json", record);
    WriteTextFileAtomically(ws / "evaluation" / "model" / "evaluation.json",
                            R"({"all": {"cells": 188400, "rms_mm": 0.05},
                                "by_clock_hour": [{"from_clock_h": 12, "rms_mm": 0.04}]})");
    ReportInputs in = GatherReportInputs(ws, ws / "run");
    in.title = "sewer3d report browser test";
    in.profile = testing_report::OvalProfile(5.0, 195.0, radius_mm);
    in.observations = std::vector<Observation>{testing_report::BumpObservation(grid, bump)};
    const ReportSummary summary = WriteReport(in, ws / "report" / "index.html");
    WriteTextFileAtomically(ws / "expected.json",
                            fmt::format(R"({{"station_mm": {}, "clock_h": {}, "radius_mm": {}, )"
                                        R"("viewer": {}, "html_bytes": {}}})",
                                        bump.station_mm, bump.clock_h, radius_mm + bump.height_mm,
                                        summary.viewer, summary.html_bytes));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "report_browser_fixture: %s\n", e.what());
    return 1;
  }
}
