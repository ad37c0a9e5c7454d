// File stamps: a replaced file is told from the stamped one, a copy with a new time is not.

#include "sewer3d/io/file_stamp.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

class FileStampTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sewer3d_file_stamp_test_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST(ContentHash, DiffersForOneChangedBitAndForLength) {
  std::string a(1001, 'x');
  const auto* p = reinterpret_cast<const std::uint8_t*>(a.data());
  const std::uint64_t h = ContentHash(p, a.size());
  for (const std::size_t at : {std::size_t{0}, std::size_t{7}, std::size_t{8}, std::size_t{1000}}) {
    std::string b = a;
    b[at] ^= 1;
    EXPECT_NE(ContentHash(reinterpret_cast<const std::uint8_t*>(b.data()), b.size()), h) << at;
  }
  EXPECT_NE(ContentHash(p, a.size() - 1), h);
  EXPECT_EQ(ContentHash(p, a.size()), h);
}

TEST_F(FileStampTest, SameFileMatchesAReplacedOneDoesNot) {
  const fs::path file = dir_ / "image.png";
  WriteTextFile(file, "pattern image of counter 0");
  const FileStamp stamp = StampFile(file);
  EXPECT_EQ(stamp.bytes, 26u);
  // Unix time: the file was written a moment ago (the file system's clock is the system's).
  const std::int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                  std::chrono::system_clock::now().time_since_epoch())
                                  .count();
  EXPECT_LT(std::abs(stamp.mtime_ns - now_ns), std::int64_t{60'000'000'000});
  EXPECT_TRUE(StillStamped(stamp, file));
  // Same size, other bytes, other time: a replaced image.
  WriteTextFile(file, "pattern image of counter 1");
  EXPECT_FALSE(StillStamped(stamp, file));
  // The original bytes back with a new time (a copy): still the file that was processed.
  WriteTextFile(file, "pattern image of counter 0");
  fs::last_write_time(file, fs::last_write_time(file) + std::chrono::hours(1));
  EXPECT_TRUE(StillStamped(stamp, file));
  fs::remove(file);
  EXPECT_FALSE(StillStamped(stamp, file));
  EXPECT_THROW(StampFile(file), FileError);
}

}  // namespace
}  // namespace sewer3d
