// workspace.json: write ∘ read is the identity; malformed files are FileErrors naming the field.

#include "sewer3d/io/workspace_io.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

WorkspaceRecord Example() {
  WorkspaceRecord record;
  record.run = "/data/runs/tiny";
  record.software_version = "0.1.0";
  WorkspaceStage rgbd;
  rgbd.options_json = R"({"max_edge_steps":5.5})";
  rgbd.done = true;
  rgbd.started_utc = "2026-12-01T20:00:00Z";
  rgbd.done_utc = "2026-12-01T20:01:30Z";
  rgbd.software_version = "0.1.0";
  rgbd.seconds = 90.25;
  rgbd.notes["color"] = "texture_before, uncorrected";
  record.stages["rgbd"] = rgbd;
  WorkspaceStage reg;  // begun, not done
  reg.options_json = R"({"a":[1,2],"b":{"c":"d"}})";
  reg.started_utc = "2026-12-01T20:02:00Z";
  record.stages["register"] = reg;
  return record;
}

void ExpectEqual(const WorkspaceRecord& a, const WorkspaceRecord& b) {
  EXPECT_EQ(a.run, b.run);
  EXPECT_EQ(a.software_version, b.software_version);
  ASSERT_EQ(a.stages.size(), b.stages.size());
  for (const auto& [name, s] : a.stages) {
    SCOPED_TRACE(name);
    const WorkspaceStage& t = b.stages.at(name);
    EXPECT_EQ(s.options_json, t.options_json);
    EXPECT_EQ(s.done, t.done);
    EXPECT_EQ(s.started_utc, t.started_utc);
    EXPECT_EQ(s.done_utc, t.done_utc);
    EXPECT_EQ(s.software_version, t.software_version);
    EXPECT_EQ(s.seconds, t.seconds);
    EXPECT_EQ(s.notes, t.notes);
  }
}

TEST(WorkspaceIo, RoundTripThroughTheFile) {
  const fs::path path = fs::temp_directory_path() / "sewer3d_workspace_io_test" / "workspace.json";
  fs::remove_all(path.parent_path());
  const WorkspaceRecord record = Example();
  WriteWorkspaceRecord(path, record);
  ExpectEqual(record, ReadWorkspaceRecord(path));
  const std::string text = ReadTextFile(path);
  EXPECT_NE(text.find(R"("format": "sewer3d-workspace")"), std::string::npos);
  EXPECT_NE(text.find(R"("done_utc": null)"), std::string::npos);  // register is not done
  fs::remove_all(path.parent_path());
}

TEST(WorkspaceIo, MalformedFilesNameTheField) {
  const fs::path path = "ws/workspace.json";
  EXPECT_THROW(WorkspaceFromJson("[]", path), FileError);
  EXPECT_THROW(WorkspaceFromJson("{", path), FileError);
  try {
    WorkspaceFromJson(R"({"format":"sewer3d-workspace","version":1,"run":"r",
                          "stages":{"rgbd":{"options":3}}})",
                      path);
    FAIL() << "expected FileError";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("stages.rgbd.options"), std::string::npos) << e.what();
  }
  EXPECT_THROW(WorkspaceFromJson(R"({"format":"other","version":1,"run":"r"})", path), FileError);
  try {  // an edited wall time is not printed back
    WorkspaceFromJson(R"({"format":"sewer3d-workspace","version":1,"run":"r",
                          "stages":{"rgbd":{"options":{},"seconds":-5}}})",
                      path);
    FAIL() << "expected FileError";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("stages.rgbd.seconds"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ReadWorkspaceRecord("/nonexistent/workspace.json"), FileError);
}

}  // namespace
}  // namespace sewer3d
