// Atomic writes: the final file appears only complete; a failing writer leaves the old file and
// no temporary behind.

#include "sewer3d/io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sewer3d_atomic_file_test_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  int FilesIn(const fs::path& folder) const {
    int n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(folder)) ++n;
    return n;
  }
  fs::path dir_;
};

TEST_F(AtomicFile, WritesThroughATemporaryWithTheSameExtensionInTheSameFolder) {
  const fs::path path = dir_ / "sub" / "depth.tiff";
  fs::path seen;
  WriteFileAtomically(path, [&](const fs::path& temporary) {
    seen = temporary;
    EXPECT_FALSE(fs::exists(path));  // the final name appears only after the rename
    WriteTextFile(temporary, "abc");
  });
  EXPECT_EQ(seen.parent_path(), path.parent_path());
  EXPECT_EQ(seen.extension(), ".tiff");
  EXPECT_NE(seen.filename(), path.filename());
  EXPECT_EQ(ReadTextFile(path), "abc");
  EXPECT_FALSE(fs::exists(seen));
  EXPECT_EQ(FilesIn(path.parent_path()), 1);
}

TEST_F(AtomicFile, AFailingWriterLeavesTheOldFileAndNoTemporary) {
  const fs::path path = dir_ / "report.json";
  WriteTextFileAtomically(path, "old");
  EXPECT_THROW(WriteFileAtomically(path,
                                   [&](const fs::path& temporary) {
                                     WriteTextFile(temporary, "half of the new");
                                     throw std::runtime_error("disk full");
                                   }),
               std::runtime_error);
  EXPECT_EQ(ReadTextFile(path), "old");
  EXPECT_EQ(FilesIn(dir_), 1);
}

TEST_F(AtomicFile, NewOutputsOfAFailedCommandAreRemovedAndReplacedOnesStay) {
  WriteTextFile(dir_ / "old.json", "before");
  {
    NewOutputs outputs;
    EXPECT_THROW(NewOutputs(), std::logic_error);  // one at a time
    WriteTextFile(dir_ / "old.json", "replaced");
    WriteTextFile(dir_ / "module.json", "new");
    WriteTextFile(dir_ / "pattern.png", "new");
    WriteTextFile(dir_ / "out" / "deeper" / "cloud.ply", "new");
  }                                        // not kept: the command failed
  EXPECT_FALSE(fs::exists(dir_ / "out"));  // the folders it made too
  EXPECT_FALSE(fs::exists(dir_ / "module.json"));
  EXPECT_FALSE(fs::exists(dir_ / "pattern.png"));
  EXPECT_EQ(ReadTextFile(dir_ / "old.json"), "replaced");
  {
    NewOutputs outputs;
    WriteTextFile(dir_ / "module.json", "new");
    outputs.Keep();
  }
  EXPECT_TRUE(fs::exists(dir_ / "module.json"));
  WriteTextFile(dir_ / "later.json", "no NewOutputs: nothing noted");
  { const NewOutputs outputs; }
  EXPECT_TRUE(fs::exists(dir_ / "later.json"));
}

TEST_F(AtomicFile, ReplacesAnExistingFile) {
  const fs::path path = dir_ / "workspace.json";
  WriteTextFileAtomically(path, "first");
  WriteTextFileAtomically(path, "second");
  EXPECT_EQ(ReadTextFile(path), "second");
  EXPECT_EQ(FilesIn(dir_), 1);
  EXPECT_TRUE(IsRegularFile(path));
  EXPECT_FALSE(IsRegularFile(dir_));
  EXPECT_FALSE(IsRegularFile(dir_ / "missing"));
}

TEST_F(AtomicFile, RenameFailureIsAFileErrorNamingTheFinalPath) {
  const fs::path path = dir_ / "a_folder";
  fs::create_directories(path / "not_empty");
  try {
    WriteTextFileAtomically(path, "text");
    FAIL() << "expected FileError";
  } catch (const FileError& e) {
    EXPECT_EQ(e.path(), path);
  }
  EXPECT_EQ(FilesIn(dir_), 1);  // the temporary is gone
}

TEST_F(AtomicFile, RemoveFolderRemovesATreeAndAcceptsAMissingOne) {
  WriteTextFileAtomically(dir_ / "x" / "y" / "z.txt", "z");
  RemoveFolder(dir_ / "x");
  EXPECT_FALSE(fs::exists(dir_ / "x"));
  EXPECT_NO_THROW(RemoveFolder(dir_ / "x"));
}

}  // namespace
}  // namespace sewer3d
