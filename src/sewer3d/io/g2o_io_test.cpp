#include "sewer3d/io/g2o_io.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "sewer3d/io/file_error.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

const char* kVertex0 = "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n";
const char* kVertex1 = "VERTEX_SE3:QUAT 1 1.5 0.2 -0.1 0.1 0 0 0.99498744\n";
const char* kInfo = " 100 0 0 0 0 0 100 0 0 0 0 100 0 0 0 25 0 0 25 0 25";

class G2oTest : public ::testing::Test {
 protected:
  fs::path Write(const std::string& text) {
    const fs::path path =
        fs::temp_directory_path() /
        ("sewer3d_g2o_" + std::to_string(::getpid()) + "_" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".g2o");
    std::ofstream(path) << text;
    paths_.push_back(path);
    return path;
  }
  void TearDown() override {
    for (const auto& p : paths_) fs::remove(p);
  }
  void ExpectError(const std::string& text, const std::string& needle) {
    const fs::path path = Write(text);
    try {
      ReadG2o(path);
      ADD_FAILURE() << "no error for: " << needle;
    } catch (const FileError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path.string()), std::string::npos) << what;
      EXPECT_NE(what.find(needle), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos);
    }
  }
  std::vector<fs::path> paths_;
};

TEST_F(G2oTest, RoundTripIsExact) {
  const std::string text = std::string(kVertex0) + kVertex1 +
                           "EDGE_SE3:QUAT 0 1 1.5 0.2 -0.1 0.1 0 0 0.99498744" + kInfo +
                           "\nFIX 0\n";
  const PoseGraph graph = ReadG2o(Write(text));
  ASSERT_EQ(graph.nodes().size(), 2u);
  ASSERT_EQ(graph.edges().size(), 1u);
  EXPECT_DOUBLE_EQ(graph.edges()[0].information(3, 3), 25.0);
  EXPECT_EQ(graph.fixed_nodes(), std::vector<int>{0});
  EXPECT_NEAR(graph.node(1).rotation.norm(), 1.0, 1e-15);  // normalised on read
  const fs::path out = Write("");
  WriteG2o(out, graph);
  const PoseGraph again = ReadG2o(out);
  EXPECT_EQ((again.node(1).translation - graph.node(1).translation).norm(), 0.0);
  EXPECT_EQ(again.node(1).rotation.coeffs(), graph.node(1).rotation.coeffs());
  EXPECT_EQ(again.edges()[0].information, graph.edges()[0].information);
  EXPECT_EQ(again.fixed_nodes(), graph.fixed_nodes());
}

TEST_F(G2oTest, MalformedFilesNameTheLine) {
  const std::string v = std::string(kVertex0) + kVertex1;
  ExpectError(v + "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 100 0\n",
              "line 3: EDGE_SE3:QUAT needs 30 values");
  ExpectError(v + "VERTEX_SE3:QUAT 2 1 2 3 0 0 0\n", "line 3: VERTEX_SE3:QUAT needs 8 values");
  ExpectError(v + "VERTEX_SE3:QUAT 2 1 nan 3 0 0 0 1\n", "line 3: value 3 is nan");
  ExpectError(v + "VERTEX_SE3:QUAT 2 1 abc 3 0 0 0 1\n", "line 3: 'abc' is not a number");
  ExpectError(v + "VERTEX_SE3:QUAT 2 1 2 3 0 0 0 0\n", "line 3: quaternion norm 0 is not 1");
  ExpectError(v + "VERTEX_SE3:QUAT 2 1 2 3 0 0 0 1.2\n", "line 3: quaternion norm 1.2 is not 1");
  ExpectError(v + "VERTEX_SE3:QUAT 1 1 2 3 0 0 0 1\n", "line 3: vertex 1 defined twice");
  ExpectError(v + "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 -1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n",
              "line 3: information matrix is not positive definite");
  ExpectError(v + "EDGE_SE3:QUAT 0 7 1 0 0 0 0 0 1" + kInfo + "\n",
              "line 3: edge names vertex 7, which the file does not define");
  ExpectError(v + "EDGE_SE3:QUAT 1 1 1 0 0 0 0 0 1" + kInfo + "\n",
              "line 3: edge from vertex 1 to itself");
  ExpectError(v + "VERTEX_SE2 3 0 0 0\n", "line 3: unsupported element 'VERTEX_SE2'");
  ExpectError(v + "VERTEX_SE3:QUAT -4 1 2 3 0 0 0 1\n", "line 3: '-4' is not a vertex id");
  ExpectError("# only a comment\n", "no VERTEX_SE3:QUAT");
  EXPECT_THROW(ReadG2o("/nonexistent/graph.g2o"), FileError);
}

TEST_F(G2oTest, NearUnitQuaternionsWithFewDigitsAreNormalised) {
  const PoseGraph graph = ReadG2o(Write("VERTEX_SE3:QUAT 0 0 0 0 0.7071 0 0 0.7071\n"));
  EXPECT_NEAR(graph.node(0).rotation.norm(), 1.0, 1e-15);
}

}  // namespace
}  // namespace sewer3d
