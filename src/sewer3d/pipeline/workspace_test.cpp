// The workspace record: a new workspace, resuming with the same options, refusing other
// options or another run, --force removing the stage's outputs, seconds and command entries.

#include "sewer3d/pipeline/workspace.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/io/workspace_io.hpp"
#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

class WorkspaceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / "sewer3d_workspace_test";
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(WorkspaceTest, RecordsRunVersionOptionsAndDone) {
  Workspace ws(dir_ / "ws", dir_ / "run" / "");
  EXPECT_FALSE(fs::exists(ws.RecordFile()));  // written by the first stage only
  ws.BeginStage("rgbd", R"({"a":1})", false);
  WorkspaceRecord r = ReadWorkspaceRecord(ws.RecordFile());
  EXPECT_EQ(r.run, (fs::absolute(dir_) / "run").lexically_normal().string());
  EXPECT_EQ(r.software_version, SoftwareVersion());
  EXPECT_FALSE(SoftwareVersion().empty());
  ASSERT_EQ(r.stages.count("rgbd"), 1u);
  EXPECT_FALSE(r.stages["rgbd"].done);
  EXPECT_FALSE(r.stages["rgbd"].started_utc.empty());
  EXPECT_EQ(r.stages["rgbd"].options_json, R"({"a":1})");
  ws.FinishStage("rgbd", true, {{"color", "texture_before, uncorrected"}});
  r = ReadWorkspaceRecord(ws.RecordFile());
  EXPECT_TRUE(r.stages["rgbd"].done);
  EXPECT_EQ(r.stages["rgbd"].done_utc.size(), 20u);  // 2026-12-01T20:00:00Z
  EXPECT_EQ(r.stages["rgbd"].notes["color"], "texture_before, uncorrected");
}

TEST_F(WorkspaceTest, SameOptionsResumeAndKeepOutputs) {
  {
    Workspace ws(dir_ / "ws", dir_ / "run");
    ws.BeginStage("rgbd", R"({"a":1})", false);
    WriteTextFile(ws.StageFolder("rgbd") / "kept.txt", "x");
  }
  Workspace again(dir_ / "ws", dir_ / "run");  // reopened from workspace.json
  EXPECT_EQ(again.record().stages.at("rgbd").options_json, R"({"a":1})");
  again.BeginStage("rgbd", R"({"a":1})", false);
  EXPECT_TRUE(fs::exists(again.StageFolder("rgbd") / "kept.txt"));
}

TEST_F(WorkspaceTest, ChangedOutputsMakeTheLaterStagesStaleAndTheyStartAfresh) {
  Workspace ws(dir_ / "ws", dir_ / "run");
  for (const char* stage : {"rgbd", "register", "model"}) {
    ws.BeginStage(stage, "{}", false);
    WriteTextFile(ws.StageFolder(OutputFolderName(stage)) / "made.txt", "x");
    ws.FinishStage(stage, true, {});
  }
  // A resumed rgbd that found nothing to do leaves the later stages done.
  ws.BeginStage("rgbd", "{}", false);
  ws.FinishStage("rgbd", true, {}, /*changed=*/false);
  EXPECT_TRUE(ws.record().stages.at("register").done);
  EXPECT_TRUE(ws.record().stages.at("model").done);
  // One that redid an acquisition: register and model are out of date, on disk too.
  ws.BeginStage("rgbd", "{}", false);
  ws.FinishStage("rgbd", true, {});
  WorkspaceRecord r = ReadWorkspaceRecord(ws.RecordFile());
  for (const char* stage : {"register", "model"}) {
    EXPECT_FALSE(r.stages.at(stage).done) << stage;
    EXPECT_TRUE(r.stages.at(stage).stale) << stage;
  }
  EXPECT_FALSE(r.stages.at("rgbd").stale);
  EXPECT_TRUE(fs::exists(ws.StageFolder("rgbd") / "made.txt"));
  // The stale register starts afresh (its pairs were made from the old acquisitions).
  ws.BeginStage("register", "{}", false);
  EXPECT_FALSE(fs::exists(ws.StageFolder("registration") / "made.txt"));
  EXPECT_TRUE(fs::exists(ws.StageFolder("model") / "made.txt"));  // until it runs
  EXPECT_FALSE(ws.record().stages.at("register").stale);
  EXPECT_TRUE(ws.record().stages.at("model").stale);
}

// A run whose own files exist (their content only matters for the stamps).
CaptureRun FakeRun(const fs::path& folder) {
  CaptureRun run;
  run.folder = folder;
  run.rig.modules.resize(2);
  for (RigModule& m : run.rig.modules) m.module.pattern.matrix_path = "pattern.png";  // shared
  for (const char* name : {"rig.json", "acquisitions.csv", "odometry.csv", "pattern.png"})
    WriteTextFile(folder / name, std::string(name) + " as captured\n");
  return run;
}

TEST_F(WorkspaceTest, AKeyOutputEditedOrCopiedInIsToldFromTheOneTheStageWrote) {
  const fs::path poses = dir_ / "ws" / "registration" / "poses.csv";
  {
    Workspace ws(dir_ / "ws", dir_ / "run");
    ws.BeginStage("register", "{}", false);
    WriteTextFile(poses, "module,counter\n0,0\n");
    ws.FinishStage("register", true, {});
    EXPECT_EQ(ws.ChangedOutput("register"), "");
    EXPECT_EQ(ws.ChangedOutput("model"), "");  // not recorded
  }
  Workspace again(dir_ / "ws", dir_ / "run");  // the stamp is read back from workspace.json
  EXPECT_EQ(again.ChangedOutput("register"), "");
  // The same bytes written again (a copy with a new time) are still the stage's file.
  WriteTextFile(poses, "module,counter\n0,0\n");
  EXPECT_EQ(again.ChangedOutput("register"), "");
  WriteTextFile(poses, "module,counter\n0,1\n");  // edited, or another workspace's
  EXPECT_EQ(again.ChangedOutput("register"), poses.string());
  fs::remove(poses);
  EXPECT_EQ(again.ChangedOutput("register"), poses.string());
  // A stage that did not end done stamps nothing.
  again.BeginStage("register", "{}", true);
  again.FinishStage("register", false, {});
  EXPECT_EQ(again.ChangedOutput("register"), "");
}

TEST_F(WorkspaceTest, AChangedRunFileMakesTheStagesThatUseItStale) {
  const CaptureRun run = FakeRun(dir_ / "run");
  {
    Workspace ws(dir_ / "ws", run);
    EXPECT_TRUE(ws.run_file_changes().empty());
    for (const char* stage : {"rgbd", "register", "model"}) {
      ws.BeginStage(stage, "{}", false);
      WriteTextFile(ws.StageFolder(OutputFolderName(stage)) / "made.txt", "x");
      ws.FinishStage(stage, true, {});
    }
    EXPECT_EQ(ReadWorkspaceRecord(ws.RecordFile()).run_files.size(), 4u);
  }
  EXPECT_TRUE(Workspace(dir_ / "ws", run).run_file_changes().empty());  // nothing changed

  WriteTextFile(run.folder / "odometry.csv", "odometry.csv corrected by hand\n");
  {
    Workspace ws(dir_ / "ws", run);
    ASSERT_EQ(ws.run_file_changes().size(), 1u);
    EXPECT_NE(ws.run_file_changes()[0].find("odometry.csv: changed"), std::string::npos);
    EXPECT_NE(ws.run_file_changes()[0].find("register, model start afresh"), std::string::npos)
        << ws.run_file_changes()[0];
    EXPECT_TRUE(ws.record().stages.at("rgbd").done);
    EXPECT_TRUE(ws.record().stages.at("register").stale);
    EXPECT_FALSE(ws.record().stages.at("model").done);
    ws.BeginStage("register", "{}", false);  // afresh, and the new stamps are recorded
    EXPECT_FALSE(fs::exists(ws.StageFolder("registration") / "made.txt"));
    EXPECT_TRUE(fs::exists(ws.StageFolder("rgbd") / "made.txt"));
  }
  EXPECT_TRUE(Workspace(dir_ / "ws", run).run_file_changes().empty());

  // An inclinometer added to the run after the stages ran, then removed: register afresh.
  CaptureRun with = run;
  WriteTextFile(run.folder / "inclinometer.csv", "time_s,down_x,down_y,down_z\n0,0,1,0\n");
  with.inclinometer = {InclinometerReading{}};
  for (const auto& [r, what] :
       {std::pair{&std::as_const(with), "added"}, std::pair{&run, "removed"}}) {
    Workspace ws(dir_ / "ws", *r);
    ASSERT_EQ(ws.run_file_changes().size(), 1u) << what;
    EXPECT_NE(ws.run_file_changes()[0].find(std::string("inclinometer.csv: ") + what),
              std::string::npos)
        << ws.run_file_changes()[0];
    EXPECT_TRUE(ws.record().stages.at("register").stale);
    EXPECT_TRUE(ws.record().stages.at("rgbd").done);
    ws.BeginStage("register", "{}", false);
  }
  EXPECT_TRUE(Workspace(dir_ / "ws", run).run_file_changes().empty());

  WriteTextFile(run.folder / "pattern.png", "another matrix\n");  // feeds rgbd: all afresh
  Workspace ws(dir_ / "ws", run);
  ASSERT_EQ(ws.run_file_changes().size(), 1u);
  EXPECT_NE(ws.run_file_changes()[0].find("rgbd, register, model"), std::string::npos);
  EXPECT_TRUE(ws.record().stages.at("rgbd").stale);
}

TEST_F(WorkspaceTest, OtherOptionsAreRefusedUnlessForcedAndForcingRemovesOutputs) {
  Workspace ws(dir_ / "ws", dir_ / "run");
  ws.BeginStage("rgbd", R"({"a":1})", false);
  ws.FinishStage("rgbd", true, {});
  WriteTextFile(ws.StageFolder("rgbd") / "old.txt", "x");
  try {
    ws.BeginStage("rgbd", R"({"a":2})", false);
    FAIL() << "expected WorkspaceConflict";
  } catch (const WorkspaceConflict& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("workspace.json"), std::string::npos) << what;
    EXPECT_NE(what.find("--force"), std::string::npos) << what;
    EXPECT_NE(what.find("(a 1, now 2)"), std::string::npos) << what;
  }
  EXPECT_TRUE(ReadWorkspaceRecord(ws.RecordFile()).stages["rgbd"].done);  // unchanged
  ws.BeginStage("rgbd", R"({"a":2})", true);
  EXPECT_FALSE(fs::exists(ws.StageFolder("rgbd") / "old.txt"));
  const WorkspaceRecord r = ReadWorkspaceRecord(ws.RecordFile());
  EXPECT_EQ(r.stages.at("rgbd").options_json, R"({"a":2})");
  EXPECT_FALSE(r.stages.at("rgbd").done);
}

TEST_F(WorkspaceTest, StagesRecordTheirSecondsAndCommandEntriesAreNeverRefused) {
  Workspace ws(dir_ / "ws", dir_ / "run");
  ws.BeginStage("rgbd", "{}", false);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ws.FinishStage("rgbd", true, {});
  const double seconds = ReadWorkspaceRecord(ws.RecordFile()).stages.at("rgbd").seconds;
  EXPECT_GE(seconds, 0.05);
  EXPECT_LT(seconds, 30.0);
  ws.RecordCommand("process", R"({"resolution_mm":0.2})", false, 0.0, {});
  ws.RecordCommand("process", R"({"resolution_mm":0.5})", true, 12.5, {{"skipped", "rgbd"}});
  const WorkspaceRecord r = ReadWorkspaceRecord(ws.RecordFile());
  const WorkspaceStage& p = r.stages.at("process");
  EXPECT_EQ(p.options_json, R"({"resolution_mm":0.5})");
  EXPECT_TRUE(p.done);
  EXPECT_EQ(p.seconds, 12.5);
  EXPECT_EQ(p.notes.at("skipped"), "rgbd");
  EXPECT_FALSE(fs::exists(ws.StageFolder("process")));
  EXPECT_EQ(r.stages.at("rgbd").seconds, seconds);  // other entries untouched
}

TEST_F(WorkspaceTest, AWorkspaceOfAnotherRunIsRefused) {
  {
    Workspace ws(dir_ / "ws", dir_ / "run_a");
    ws.BeginStage("rgbd", "{}", false);
  }
  EXPECT_THROW(Workspace(dir_ / "ws", dir_ / "run_b"), WorkspaceConflict);
  EXPECT_NO_THROW(Workspace(dir_ / "ws", dir_ / "." / "run_a"));
}

TEST_F(WorkspaceTest, OneProcessAtATimeAndStaleTemporariesAreRemoved) {
  std::optional<Workspace> first;
  first.emplace(dir_ / "ws", dir_ / "run_a");
  EXPECT_THROW(Workspace(dir_ / "ws", dir_ / "run_a"), FileError);
  first->BeginStage("rgbd", "{}", false);  // a stage records itself before it writes
  first.reset();  // the lock goes with the workspace (and with a killed process)
  fs::create_directories(dir_ / "ws" / "rgbd" / ".m0.tmp-12-3");
  std::ofstream(dir_ / "ws" / "rgbd" / ".m0.tmp-12-3" / "depth.tiff") << "partial";
  std::ofstream(dir_ / "ws" / "rgbd" / ".000001_report.json.tmp-12-4.json") << "{";
  std::ofstream(dir_ / "ws" / "rgbd" / "kept.txt") << "kept";
  const Workspace ws(dir_ / "ws", dir_ / "run_a");
  EXPECT_EQ(ws.stale_temporaries_removed(), 2);
  EXPECT_FALSE(fs::exists(dir_ / "ws" / "rgbd" / ".m0.tmp-12-3"));
  EXPECT_TRUE(fs::exists(dir_ / "ws" / "rgbd" / "kept.txt"));
}

// Stage outputs without workspace.json (removed, or folders copied in): nothing says which run
// and options made them, so no stage resumes from them and no evaluation reads them.
TEST_F(WorkspaceTest, StageOutputsWithoutARecordAreRefused) {
  fs::create_directories(dir_ / "ws" / "model");
  try {
    const Workspace ws(dir_ / "ws", dir_ / "run_a");
    ADD_FAILURE() << "opened";
  } catch (const WorkspaceConflict& e) {
    EXPECT_NE(std::string(e.what()).find("(model/) but no workspace.json"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(CheckWorkspaceOfRun(dir_ / "ws", dir_ / "run_a"), FileError);
  fs::remove_all(dir_ / "ws" / "model");
  EXPECT_NO_THROW(Workspace(dir_ / "ws", dir_ / "run_a"));
}

}  // namespace
}  // namespace sewer3d
