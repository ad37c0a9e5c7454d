#include "sewer3d/io/g2o_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/input_file.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

constexpr double kQuaternionNormTolerance = 1e-3;

class LineParser {
 public:
  LineParser(const std::filesystem::path& path, int line_number, const std::string& line)
      : path_(path), line_number_(line_number) {
    std::istringstream in(line);
    std::string token;
    while (in >> token) tokens_.push_back(token);
  }

  [[noreturn]] void Fail(const std::string& problem) const {
    throw FileError(path_, "line " + std::to_string(line_number_) + ": " + problem);
  }
  const std::string& tag() const { return tokens_.front(); }
  bool empty() const { return tokens_.empty() || tokens_.front().starts_with('#'); }
  void ExpectCount(size_t count, const char* what) const {
    if (tokens_.size() != count) {
      Fail(std::string(what) + " needs " + std::to_string(count - 1) + " values, found " +
           std::to_string(tokens_.size() - 1));
    }
  }
  int Id(size_t i) const {
    const std::string& t = tokens_[i];
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(t.c_str(), &end, 10);
    if (end == t.c_str() || *end != '\0' || errno != 0 || v < 0 || v > 2'000'000'000) {
      Fail("'" + t + "' is not a vertex id");
    }
    return static_cast<int>(v);
  }
  double Number(size_t i) const {
    const std::string& t = tokens_[i];
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (end == t.c_str() || *end != '\0') Fail("'" + t + "' is not a number");
    if (!std::isfinite(v)) Fail("value " + std::to_string(i) + " is " + t + " (not finite)");
    return v;
  }
  static constexpr double kMaxTranslation = 1e9;
  /// Translation and quaternion from tokens first..first+6.
  Rigid3d Pose(size_t first) const {
    const Eigen::Vector3d t(Number(first), Number(first + 1), Number(first + 2));
    // Positions beyond 1e9 (a thousand km in mm, or in any unit a pose graph uses) are no
    // survey: their squares overflow the solver's cost.
    if (!(t.cwiseAbs().maxCoeff() <= kMaxTranslation)) {
      std::ostringstream out;
      out << "translation (" << t.x() << ", " << t.y() << ", " << t.z() << ") is beyond ±"
          << kMaxTranslation;
      Fail(out.str());
    }
    const Eigen::Quaterniond q(Number(first + 6), Number(first + 3), Number(first + 4),
                               Number(first + 5));
    const double norm = q.norm();
    if (!(std::abs(norm - 1.0) <= kQuaternionNormTolerance)) {
      std::ostringstream out;
      out << "quaternion norm " << norm << " is not 1";
      Fail(out.str());
    }
    return Rigid3d(q, t);  // normalises
  }

 private:
  const std::filesystem::path& path_;
  int line_number_;
  std::vector<std::string> tokens_;
};

}  // namespace

PoseGraph ReadG2o(const std::filesystem::path& path) {
  CheckInputFile(path, std::numeric_limits<std::uintmax_t>::max());
  std::ifstream file(path);
  if (!file) throw FileError(path, "cannot open file");
  PoseGraph graph;
  struct PendingEdge {
    PoseEdge edge;
    int line;
  };
  std::vector<PendingEdge> pending;
  std::vector<std::pair<int, int>> fixes;  // (id, line)
  std::string line;
  int number = 0;
  while (std::getline(file, line)) {
    ++number;
    if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 BOM
    if (line.find('\0') != std::string::npos)
      throw FileError(path, "line " + std::to_string(number) + ": a NUL byte: not a text file");
    // g2o is ASCII: another byte (a PNG's 0x89, a control character) means another kind of file,
    // named by its value rather than printed raw.
    const auto odd = std::find_if(line.begin(), line.end(), [](char c) {
      const auto b = static_cast<unsigned char>(c);
      return b >= 0x80 || (b < 0x20 && c != '\t' && c != '\r');
    });
    const size_t first = line.find_first_not_of(" \t");
    if (odd != line.end() && (first == std::string::npos || line[first] != '#')) {
      throw FileError(
          path, fmt::format("line {}: byte 0x{:02X} at column {}: not a g2o text file "
                            "(g2o is ASCII)",
                            number, static_cast<unsigned char>(*odd), odd - line.begin() + 1));
    }
    const LineParser in(path, number, line);
    if (in.empty()) continue;
    if (in.tag() == "VERTEX_SE3:QUAT") {
      in.ExpectCount(9, "VERTEX_SE3:QUAT");
      const int id = in.Id(1);
      if (graph.HasNode(id)) in.Fail("vertex " + std::to_string(id) + " defined twice");
      graph.SetNode(id, in.Pose(2));
    } else if (in.tag() == "EDGE_SE3:QUAT") {
      in.ExpectCount(31, "EDGE_SE3:QUAT");
      PoseEdge edge;
      edge.from = in.Id(1);
      edge.to = in.Id(2);
      if (edge.from == edge.to)
        in.Fail("edge from vertex " + std::to_string(edge.from) + " to itself");
      edge.a_from_b = in.Pose(3);
      size_t k = 10;
      for (int r = 0; r < 6; ++r) {
        for (int c = r; c < 6; ++c)
          edge.information(r, c) = edge.information(c, r) = in.Number(k++);
      }
      if (!IsSymmetricPositiveDefinite(edge.information)) {
        in.Fail("information matrix is not positive definite");
      }
      pending.push_back({edge, number});
    } else if (in.tag() == "FIX") {
      in.ExpectCount(2, "FIX");
      fixes.emplace_back(in.Id(1), number);
    } else {
      in.Fail("unsupported element '" + in.tag() +
              "' (expected VERTEX_SE3:QUAT, EDGE_SE3:QUAT or FIX)");
    }
  }
  if (file.bad()) throw FileError(path, "read error");
  for (const auto& [edge, edge_line] : pending) {
    for (int id : {edge.from, edge.to}) {
      if (!graph.HasNode(id)) {
        throw FileError(path, "line " + std::to_string(edge_line) + ": edge names vertex " +
                                  std::to_string(id) + ", which the file does not define");
      }
    }
    graph.AddEdge(edge);
  }
  for (const auto& [id, fix_line] : fixes) {
    if (!graph.HasNode(id)) {
      throw FileError(path, "line " + std::to_string(fix_line) + ": FIX names undefined vertex " +
                                std::to_string(id));
    }
    graph.fixed_nodes().push_back(id);
  }
  if (graph.nodes().empty()) throw FileError(path, "no VERTEX_SE3:QUAT in file");
  return graph;
}

void WriteG2o(const std::filesystem::path& path, const PoseGraph& graph) {
  std::ostringstream file;
  file.precision(17);
  auto write_pose = [&file](const Rigid3d& pose) {
    const Eigen::Vector3d& t = pose.translation;
    const Eigen::Quaterniond& q = pose.rotation;
    file << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z()
         << ' ' << q.w();
  };
  for (const auto& [id, pose] : graph.nodes()) {
    file << "VERTEX_SE3:QUAT " << id << ' ';
    write_pose(pose);
    file << '\n';
  }
  for (const PoseEdge& e : graph.edges()) {
    file << "EDGE_SE3:QUAT " << e.from << ' ' << e.to << ' ';
    write_pose(e.a_from_b);
    for (int r = 0; r < 6; ++r) {
      for (int c = r; c < 6; ++c) file << ' ' << e.information(r, c);
    }
    file << '\n';
  }
  for (int id : graph.fixed_nodes()) file << "FIX " << id << '\n';
  WriteTextFile(path, file.str());
}

}  // namespace sewer3d
