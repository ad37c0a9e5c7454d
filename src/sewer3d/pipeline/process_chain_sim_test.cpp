// The chain of stages over the tiny simulated run (2 acquisitions × 6 modules, 648 × 486): bad
// acquisitions (a truncated pattern image, a missing texture image) are left out and listed,
// the chain goes on and makes the model from the rest; once the input is mended the chain
// resumes, redoing only those acquisitions; run again, every stage is skipped from
// workspace.json.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/model_io.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/io/workspace_io.hpp"
#include "sewer3d/pipeline/process_chain.hpp"
#include "sewer3d/pipeline/report_stage.hpp"
#include "sewer3d/pipeline/tiny_run_sim_test.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ProcessChainTiny, LeavesOutBadAcquisitionsResumesAndSkipsWhatIsDone) {
  const fs::path dir = fs::temp_directory_path() / "sewer3d_process_chain_sim_test";
  fs::remove_all(dir);
  testing::MakeTinyRun(dir / "run");
  ProcessOptions options;
  options.threads = 2;
  options.resolution_mm = 0.5;
  options.start_station_mm = 1200.0;

  // A truncated pattern image and a missing texture image: those two acquisitions are left
  // out and listed, the other ten make the model.
  const fs::path image = dir / "run" / "images" / (ImageStem(3, 1, ImageKind::kPattern) + ".png");
  const fs::path texture =
      dir / "run" / "images" / (ImageStem(1, 1, ImageKind::kTextureAfter) + ".png");
  const std::string bytes = ReadTextFile(image), texture_bytes = ReadTextFile(texture);
  WriteTextFile(image, bytes.substr(0, bytes.size() / 2));
  fs::remove(texture);
  std::set<std::string> passes;
  {
    const CaptureRun run = LoadRun(dir / "run");
    Workspace ws(dir / "ws", run.folder);
    const ProcessReport report = RunProcess(
        run, ws, options, [&](const std::string& pass, int, int) { passes.insert(pass); });
    EXPECT_TRUE(report.ok);
    ASSERT_EQ(report.stages.size(), 5u);
    for (const ProcessStageResult& r : report.stages) EXPECT_TRUE(r.outcome.ok) << r.name;
    const StageOutcome& rgbd = report.stages[0].outcome;
    EXPECT_TRUE(Contains(rgbd.summary, "10 done, 0 skipped (done before), 2 failed"))
        << rgbd.summary;
    ASSERT_EQ(rgbd.details.size(), 2u);
    EXPECT_TRUE(Contains(rgbd.details[0], "m1 counter 1 left out: "));
    EXPECT_TRUE(Contains(rgbd.details[0],
                         "000001_texture_after.png: listed in acquisitions.csv but missing"))
        << rgbd.details[0];
    EXPECT_TRUE(Contains(rgbd.details[1], "m3 counter 1 left out: "));
    EXPECT_TRUE(Contains(rgbd.details[1], "000001_pattern.png: cannot decode image"))
        << rgbd.details[1];
    EXPECT_EQ(passes.count("model tiles"), 1u);
    EXPECT_TRUE(Contains(report.stages[1].outcome.summary, "12 acquisitions, 10 nodes, 2 left out"))
        << report.stages[1].outcome.summary;
  }
  const nlohmann::json failures =
      nlohmann::json::parse(ReadTextFile(dir / "ws" / "rgbd" / "report.json"))["failures"];
  ASSERT_EQ(failures.size(), 2u);
  EXPECT_EQ(failures[1]["module"], 3);
  EXPECT_EQ(failures[1]["counter"], 1);
  EXPECT_EQ(failures[1]["file"], image.string());
  EXPECT_TRUE(Contains(failures[1]["reason"].get<std::string>(), "truncated"));
  EXPECT_TRUE(fs::exists(dir / "ws" / "model" / "model.json"));
  EXPECT_TRUE(fs::exists(dir / "ws" / "report" / "index.html"));
  WorkspaceRecord record = ReadWorkspaceRecord(dir / "ws" / "workspace.json");
  EXPECT_FALSE(record.stages.at("rgbd").done);  // so that the next process retries them
  EXPECT_EQ(record.stages.at("rgbd").notes.at("failed"), "2");
  EXPECT_TRUE(record.stages.at("register").done);
  EXPECT_TRUE(record.stages.at("process").done);
  EXPECT_EQ(
      record.stages.at("process").options_json,
      R"({"resolution_mm":0.5,"stages":["rgbd","register","model","inspect","report"],"start_station_mm":1200.0})");

  // Mended: the rgbd stage redoes the two acquisitions, register, model and inspect run again.
  WriteTextFile(image, bytes);
  WriteTextFile(texture, texture_bytes);
  const CaptureRun run = LoadRun(dir / "run");
  {
    Workspace ws(dir / "ws", run.folder);
    const ProcessReport report = RunProcess(run, ws, options);
    EXPECT_TRUE(report.ok);
    ASSERT_EQ(report.stages.size(), 5u);
    EXPECT_EQ(report.stages[0].name, "rgbd");
    EXPECT_EQ(report.stages[1].name, "register");
    EXPECT_EQ(report.stages[2].name, "model");
    EXPECT_EQ(report.stages[3].name, "inspect");
    EXPECT_EQ(report.stages[4].name, "report");
    for (const ProcessStageResult& r : report.stages) EXPECT_FALSE(r.skipped) << r.name;
    EXPECT_TRUE(Contains(report.stages[0].outcome.summary, "2 done, 10 skipped"))
        << report.stages[0].outcome.summary;
    EXPECT_TRUE(report.stages[0].outcome.details.empty());
    EXPECT_TRUE(Contains(report.stages[1].outcome.summary, "12 nodes, 0 left out"));
    EXPECT_TRUE(fs::exists(dir / "ws" / "registration" / "poses.csv"));
    EXPECT_TRUE(fs::exists(dir / "ws" / "inspection" / "observations.json"));
    EXPECT_TRUE(fs::exists(dir / "ws" / "report" / "index.html"));
    // The model took the chain's grid and start station: the carrier's first position is
    // station 1200, the rearmost camera looks ~315 mm behind it.
    const PipeModelInfo model = ReadModelJson(dir / "ws" / "model" / "model.json");
    EXPECT_DOUBLE_EQ(model.grid.resolution_mm, 0.5);
    EXPECT_DOUBLE_EQ(model.start_station_mm, 1200.0);
    EXPECT_NEAR(model.grid.station0_mm, 1200.0 - 315.0, 30.0);
  }
  record = ReadWorkspaceRecord(dir / "ws" / "workspace.json");
  for (const char* stage : {"rgbd", "register", "model", "inspect", "report", "process"}) {
    SCOPED_TRACE(stage);
    EXPECT_TRUE(record.stages.at(stage).done);
    EXPECT_GT(record.stages.at(stage).seconds, 0.0);
  }
  EXPECT_LE(record.stages.at("rgbd").seconds + record.stages.at("register").seconds +
                record.stages.at("model").seconds + record.stages.at("inspect").seconds +
                record.stages.at("report").seconds,
            record.stages.at("process").seconds);

  // Again: every stage recorded done with the same options, none is started.
  {
    Workspace ws(dir / "ws", run.folder);
    const ProcessReport again = RunProcess(run, ws, options);
    EXPECT_TRUE(again.ok);
    ASSERT_EQ(again.stages.size(), 5u);
    for (const ProcessStageResult& r : again.stages) {
      EXPECT_TRUE(r.skipped) << r.name;
      EXPECT_EQ(r.seconds, record.stages.at(r.name).seconds);  // as recorded
    }
  }
  EXPECT_EQ(
      ReadWorkspaceRecord(dir / "ws" / "workspace.json").stages.at("process").notes.at("skipped"),
      "rgbd register model inspect report");

  // An observation edited to 250 m, far beyond the model's stations: the report refuses it.
  const fs::path observations = dir / "ws" / "inspection" / "observations.json";
  nlohmann::json o = nlohmann::json::parse(ReadTextFile(observations));
  ASSERT_FALSE(o.at("observations").empty());  // the tiny run's joint, at least
  o["observations"][0]["station_mm"] = 250000.0;
  WriteTextFile(observations, o.dump(1));
  {
    Workspace ws(dir / "ws", run.folder);
    try {
      RunReportStage(run, ws, true);
      ADD_FAILURE() << "an observation at 250 m was reported";
    } catch (const FileError& e) {
      EXPECT_TRUE(Contains(e.what(), "lies outside the model's stations")) << e.what();
    }
  }
  if (!std::getenv("SEWER3D_KEEP")) fs::remove_all(dir);
}

TEST(ProcessOptions, RejectsABadGridOrStation) {
  ProcessOptions options;
  EXPECT_NO_THROW(options.Check());
  options.resolution_mm = 0.0;
  EXPECT_THROW(options.Check(), std::invalid_argument);
  options.resolution_mm = 0.2;
  options.start_station_mm = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(options.Check(), std::invalid_argument);
  options.start_station_mm = 0.0;
  options.threads = 0;
  EXPECT_THROW(options.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
