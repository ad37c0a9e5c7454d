// `sewer3d report RUN --out WS`: WS/report/index.html, one self-contained offline page of what
// the workspace holds (docs/report.md).

#include <fmt/core.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "sewer3d/cli/command.hpp"
#include "sewer3d/report/report.hpp"
#include "sewer3d/report/workspace_inputs.hpp"
#if __has_include("sewer3d/io/inspection_io.hpp")
#include "sewer3d/io/inspection_io.hpp"
#define SEWER3D_HAVE_INSPECTION_IO 1
#endif

namespace sewer3d::cli {
namespace {

/// WS/inspection/profile.csv and observations.json when they exist (the readers belong to
/// `sewer3d inspect`; a build without them leaves both out and says so).
void AddInspection(const std::filesystem::path& ws, ReportInputs& in) {
#ifdef SEWER3D_HAVE_INSPECTION_IO
  const InspectionFiles files = InspectionFilesIn(ws);
  if (std::filesystem::exists(files.profile_csv)) in.profile = ReadProfileCsv(files.profile_csv);
  if (std::filesystem::exists(files.observations_json))
    in.observations = ReadObservationsJson(files.observations_json);
#else
  if (std::filesystem::exists(ws / "inspection"))
    in.notes.push_back(
        "This sewer3d cannot read WS/inspection/ yet: observations and profile "
        "left out.");
#endif
}

std::string Megabytes(std::uintmax_t bytes) {
  return fmt::format("{:.1f} MB", static_cast<double>(bytes) / 1e6);
}

}  // namespace

Command AddReportCommand(CLI::App& app) {
  struct Args {
    std::string run, out;
    bool quiet = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "report",
      "WS/report/index.html: one self-contained offline page with the run summary, the unrolled "
      "maps, a 3D viewer, the profile, the observations and the accuracy figures");
  sub->add_option("RUN", args->run, "Capture run folder (docs/formats.md)")->required();
  sub->add_option("--out", args->out, "Processing workspace folder WS")->required();
  sub->add_flag("--quiet", args->quiet, "Print only where the report is");
  return {sub, [args] {
            const std::filesystem::path ws = args->out;
            const auto start = std::chrono::steady_clock::now();
            ReportInputs in = GatherReportInputs(ws, args->run);
            AddInspection(ws, in);
            const std::filesystem::path html = ws / "report" / "index.html";
            const ReportSummary s = WriteReport(in, html);
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (!s.maps_problem.empty())
              fmt::print(stderr, "sewer3d: warning: report without maps: {}\n", s.maps_problem);
            if (!args->quiet) {
              for (const std::string& note : s.notes) fmt::print("note: {}\n", note);
              fmt::print(
                  "report: {}, {:.1f} s; maps {}, 3D viewer {}, {} observations, profile "
                  "{}\n",
                  Megabytes(s.html_bytes), seconds, s.maps ? "yes" : "no", s.viewer ? "yes" : "no",
                  in.observations ? std::to_string(in.observations->size()) : "no",
                  in.profile ? std::to_string(in.profile->rows.size()) + " rows" : "no");
            }
            fmt::print("wrote {}\n", html.string());
            return 0;
          }};
}

}  // namespace sewer3d::cli
