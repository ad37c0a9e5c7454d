// PLY round trips: what WritePly writes (binary little-endian, with and without colours)
// ReadPlyPoints reads back exactly (to float precision); ASCII files and other property types
// read as the format says; broken files are FileErrors naming the file.

#include "sewer3d/io/ply_io.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <random>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

// Exact equality, coordinate by coordinate.
void ExpectSamePoints(const std::vector<Eigen::Vector3d>& read,
                      const std::vector<Eigen::Vector3d>& expected) {
  ASSERT_EQ(read.size(), expected.size());
  for (size_t i = 0; i < read.size(); ++i) {
    for (int k = 0; k < 3; ++k) ASSERT_EQ(read[i][k], expected[i][k]) << "point " << i;
  }
}

class PlyIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sewer3d_ply_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> xy(-100.0, 100.0), z(75.0, 225.0);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int i = 0; i < 1000; ++i) {
      points_.emplace_back(xy(rng), xy(rng), z(rng));
      colours_.push_back({static_cast<std::uint8_t>(byte(rng)),
                          static_cast<std::uint8_t>(byte(rng)),
                          static_cast<std::uint8_t>(byte(rng))});
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The points as the file stores them: x, y, z rounded to float.
  std::vector<Eigen::Vector3d> AsFloats() const {
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : points_) out.push_back(p.cast<float>().cast<double>());
    return out;
  }

  // Byte offset of the first vertex (just after "end_header\n").
  static size_t BodyOffset(const std::string& bytes) {
    const size_t end = bytes.find("end_header\n");
    EXPECT_NE(end, std::string::npos);
    return end + std::strlen("end_header\n");
  }

  fs::path dir_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::array<std::uint8_t, 3>> colours_;
};

TEST_F(PlyIoTest, BinaryWithoutColoursRoundTrips) {
  const fs::path path = dir_ / "sub" / "cloud.ply";  // the folder is created
  WritePly(path, points_, {});
  const std::string bytes = ReadTextFile(path);
  EXPECT_EQ(bytes.find("red"), std::string::npos);
  EXPECT_EQ(bytes.size(), BodyOffset(bytes) + points_.size() * 12);  // 3 floats a vertex
  ExpectSamePoints(ReadPlyPoints(path), AsFloats());
}

TEST_F(PlyIoTest, BinaryWithColoursRoundTrips) {
  const fs::path path = dir_ / "cloud.ply";
  WritePly(path, points_, colours_);
  ExpectSamePoints(ReadPlyPoints(path), AsFloats());
  // The colours follow each vertex's x y z as uchar red green blue (the reader skips them).
  const std::string bytes = ReadTextFile(path);
  EXPECT_NE(bytes.find("property uchar red\nproperty uchar green\nproperty uchar blue\n"),
            std::string::npos);
  const size_t body = BodyOffset(bytes);
  ASSERT_EQ(bytes.size(), body + points_.size() * 15);
  for (size_t i = 0; i < points_.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(static_cast<std::uint8_t>(bytes[body + 15 * i + 12 + k]), colours_[i][k]) << i;
    }
  }
}

TEST_F(PlyIoTest, EmptyCloudRoundTrips) {
  WritePly(dir_ / "empty.ply", {}, {});
  EXPECT_TRUE(ReadPlyPoints(dir_ / "empty.ply").empty());
}

TEST_F(PlyIoTest, ReadsAsciiWithAndWithoutColours) {
  WriteTextFile(dir_ / "plain.ply",
                "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                "property float z\nend_header\n1.5 -2.25 100\n0.125 3 150.5\n");
  ExpectSamePoints(ReadPlyPoints(dir_ / "plain.ply"), {{1.5, -2.25, 100.0}, {0.125, 3.0, 150.5}});
  // Colours, a normal between the coordinates, doubles.
  WriteTextFile(dir_ / "coloured.ply",
                "ply\nformat ascii 1.0\ncomment written by hand\nelement vertex 2\n"
                "property double x\nproperty double y\nproperty float nx\nproperty double z\n"
                "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
                "0.1 0.2 1 90.123456789 255 0 7\n-4 5 0 200 1 2 3\n");
  ExpectSamePoints(ReadPlyPoints(dir_ / "coloured.ply"),
                   {{0.1, 0.2, 90.123456789}, {-4.0, 5.0, 200.0}});
}

TEST_F(PlyIoTest, ReadsBinaryDoubles) {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty uchar flag\n"
      "property double x\nproperty double y\nproperty double z\nend_header\n";
  const double xyz[3] = {0.1, -0.2, 123.456789012345};
  bytes.push_back('\x01');
  bytes.append(reinterpret_cast<const char*>(xyz), sizeof(xyz));
  WriteTextFile(dir_ / "double.ply", bytes);
  ExpectSamePoints(ReadPlyPoints(dir_ / "double.ply"), {{0.1, -0.2, 123.456789012345}});
}

// Expects ReadPlyPoints to throw a FileError naming the file and `needle`.
void ExpectReadError(const fs::path& path, const std::string& needle) {
  try {
    ReadPlyPoints(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const FileError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(needle), std::string::npos) << message;
  }
}

TEST_F(PlyIoTest, BrokenFilesAreFileErrors) {
  WritePly(dir_ / "cut.ply", points_, colours_);
  const std::string whole = ReadTextFile(dir_ / "cut.ply");
  WriteTextFile(dir_ / "cut.ply", whole.substr(0, whole.size() - 20));
  ExpectReadError(dir_ / "cut.ply", "truncated: 998 of 1000 vertices");
  WriteTextFile(dir_ / "not.ply", "solid cube\n");
  ExpectReadError(dir_ / "not.ply", "not a PLY file");
  WriteTextFile(dir_ / "no_z.ply",
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                "end_header\n1 2\n");
  ExpectReadError(dir_ / "no_z.ply", "vertices lack x, y or z");
  WriteTextFile(dir_ / "odd.ply",
                "ply\nformat binary_middle_endian 1.0\nelement vertex 1\nproperty float x\n"
                "property float y\nproperty float z\nend_header\n123456789012");
  ExpectReadError(dir_ / "odd.ply", "unsupported PLY format 'binary_middle_endian'");
  ExpectReadError(dir_ / "missing.ply", "no such file");
  ExpectReadError(dir_, "is a folder, not a file");
  WriteTextFile(dir_ / "header.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n");
  ExpectReadError(dir_ / "header.ply", "PLY header has no end_header line");
  WriteTextFile(dir_ / "list.ply",
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar int x\n"
                "end_header\n1 2\n");
  ExpectReadError(dir_ / "list.ply", "list property in vertex element");
  // end_header without its newline runs into the binary body: the bytes are quoted as \xNN.
  WriteTextFile(dir_ / "glued.ply",
                std::string("ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
                            "property float x\nproperty float y\nproperty float z\nend_header") +
                    std::string("\xd9\xaf\x01\x1bq\n", 6));
  ExpectReadError(dir_ / "glued.ply", "unknown PLY header line: end_header\\xd9\\xaf\\x01\\x1bq");
}

// A count the body does not match is an error either way, never a silently shorter cloud, and
// a count far beyond the file's size is refused before anything is allocated for it.
TEST_F(PlyIoTest, CountsMustMatchTheBody) {
  const std::string points = "1 2 3\n4 5 6\n7 8 9\n";
  const auto header = [](const std::string& count) {
    return "ply\nformat ascii 1.0\nelement vertex " + count +
           "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  };
  WriteTextFile(dir_ / "low.ply", header("2") + points);
  ExpectReadError(dir_ / "low.ply", "the body holds more than the 2 vertices the header declares");
  WriteTextFile(dir_ / "high.ply", header("4") + points);
  ExpectReadError(dir_ / "high.ply", "truncated: 3 of 4 vertices");
  WriteTextFile(dir_ / "huge.ply", header("1000000000000000000") + points);
  ExpectReadError(dir_ / "huge.ply", "truncated");
  // An element after the vertices keeps its own count.
  WriteTextFile(dir_ / "faces.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                "end_header\n" +
                    points + "3 0 1 2\n");
  ExpectSamePoints(ReadPlyPoints(dir_ / "faces.ply"), {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}});
}

// Every scalar type, either byte order: signed values keep their sign.
TEST_F(PlyIoTest, ReadsEveryScalarTypeInBothByteOrders) {
  const std::vector<Eigen::Vector3d> expected{{-100, 7, 120}, {55, -128, 127}};
  for (const bool big : {false, true}) {
    for (const auto& [type, bytes] : std::vector<std::pair<std::string, int>>{
             {"char", 1}, {"short", 2}, {"int", 4}, {"int16", 2}, {"int32", 4}, {"double", 8}}) {
      std::string body;
      for (const auto& p : expected) {
        for (int k = 0; k < 3; ++k) {
          unsigned char raw[8];
          if (type == "double") {
            std::memcpy(raw, &p[k], 8);
          } else {
            const auto v = static_cast<std::int64_t>(p[k]);
            for (int i = 0; i < bytes; ++i) raw[i] = static_cast<unsigned char>(v >> (8 * i));
          }
          for (int i = 0; i < bytes; ++i) body += static_cast<char>(raw[big ? bytes - 1 - i : i]);
        }
      }
      const fs::path file = dir_ / (type + (big ? "_big.ply" : "_little.ply"));
      WriteTextFile(file, fmt::format("ply\nformat {} 1.0\nelement vertex 2\nproperty {} "
                                      "x\nproperty {} y\nproperty {} z\nend_header\n{}",
                                      big ? "binary_big_endian" : "binary_little_endian", type,
                                      type, type, body));
      SCOPED_TRACE(file.filename().string());
      ExpectSamePoints(ReadPlyPoints(file), expected);
    }
  }
}

}  // namespace
}  // namespace sewer3d
