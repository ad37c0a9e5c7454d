// The chain of stages over the tiny simulated run (2 acquisitions × 6 modules, 648 × 486): a
// stage that fails stops the chain and keeps what it wrote; once the input is mended the chain
// resumes and runs every stage; run again, every stage is skipped from workspace.json.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <limits>
#include <set>

#include "sewer3d/io/model_io.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/io/workspace_io.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/pipeline/process_chain.hpp"
#include "sewer3d/simio/simulate_run.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

TEST(ProcessChainTiny, StopsAtAFailedStageResumesAndSkipsWhatIsDone) {
  const fs::path dir = fs::temp_directory_path() / "sewer3d_process_chain_sim_test";
  fs::remove_all(dir);
  Scenario s = PresetScenario("tiny");
  s.truth_depth = TruthDepth::kNone;
  SimulateRun(s, testing::SmallDefaultModule(s.camera_width), DefaultPatternArray(), dir / "run",
              {});
  const CaptureRun run = LoadRun(dir / "run");
  ProcessOptions options;
  options.threads = 2;
  options.resolution_mm = 0.5;
  options.start_station_mm = 1200.0;

  // A truncated pattern image fails its acquisition, so the rgbd stage fails: register is
  // never started.
  const fs::path image = dir / "run" / "images" / (ImageStem(3, 1, ImageKind::kPattern) + ".png");
  const std::string bytes = ReadTextFile(image);
  WriteTextFile(image, bytes.substr(0, bytes.size() / 2));
  std::set<std::string> passes;
  {
    Workspace ws(dir / "ws", run.folder);
    const ProcessReport failed = RunProcess(
        run, ws, options, [&](const std::string& pass, int, int) { passes.insert(pass); });
    EXPECT_FALSE(failed.ok);
    ASSERT_EQ(failed.stages.size(), 1u);
    ASSERT_NE(failed.Failure(), nullptr);
    EXPECT_EQ(failed.Failure()->name, "rgbd");
    EXPECT_NE(failed.Failure()->outcome.error.find("000001_pattern.png"), std::string::npos);
  }
  EXPECT_EQ(passes, (std::set<std::string>{"rgbd geometry", "rgbd reference", "rgbd colour"}));
  WorkspaceRecord record = ReadWorkspaceRecord(dir / "ws" / "workspace.json");
  EXPECT_EQ(record.stages.count("register"), 0u);
  EXPECT_FALSE(record.stages.at("rgbd").done);
  EXPECT_FALSE(record.stages.at("process").done);
  EXPECT_EQ(record.stages.at("process").notes.at("failed"), "rgbd");
  EXPECT_EQ(
      record.stages.at("process").options_json,
      R"({"resolution_mm":0.5,"stages":["rgbd","register","model","inspect","report"],"start_station_mm":1200.0})");

  // Mended: the rgbd stage redoes the one acquisition, register, model and inspect run.
  WriteTextFile(image, bytes);
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
    EXPECT_NE(report.stages[0].outcome.summary.find("1 done, 11 skipped"), std::string::npos)
        << report.stages[0].outcome.summary;
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
