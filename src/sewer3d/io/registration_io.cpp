#include "sewer3d/io/registration_io.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/csv.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;
constexpr const char* kPosesHeader = "module,counter,time_s,x_mm,y_mm,z_mm,qx,qy,qz,qw";
constexpr const char* kEdgesHeader =
    "from,to,from_module,from_counter,to_module,to_counter,type,inliers,rms_mm,eig0,eig1,eig2,"
    "eig3,eig4,eig5,chi2,accepted";

Rigid3d PoseFromJson(const std::filesystem::path& path, const json& j) {
  const std::vector<double> q = j.at("q_xyzw").get<std::vector<double>>();
  const std::vector<double> t = j.at("t_mm").get<std::vector<double>>();
  if (q.size() != 4 || t.size() != 3) throw FileError(path, "a_from_b needs q_xyzw[4], t_mm[3]");
  const Eigen::Quaterniond quaternion(q[3], q[0], q[1], q[2]);
  if (std::abs(quaternion.norm() - 1.0) > 1e-6) throw FileError(path, "quaternion not unit");
  return {quaternion, Eigen::Vector3d(t[0], t[1], t[2])};
}

// The node with its clock in [0, 12): the crown (12 h) on the strip's top line.
GraphPictureNode OnClockFace(GraphPictureNode n) {
  n.clock_h = std::fmod(std::fmod(n.clock_h, 12.0) + 12.0, 12.0);
  return n;
}

}  // namespace

void WriteRegistrationPoses(const std::filesystem::path& path,
                            const std::vector<RegistrationPoseRow>& rows) {
  std::string text = std::string(kPosesHeader) + "\n";
  for (const RegistrationPoseRow& r : rows) {
    const Eigen::Vector3d& p = r.world_from_camera.translation;
    const Eigen::Quaterniond& q = r.world_from_camera.rotation;
    text +=
        fmt::format("{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.12f},{:.12f},{:.12f},{:.12f}\n", r.module,
                    r.counter, r.time_s, p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w());
  }
  WriteTextFileAtomically(path, text);
}

std::vector<RegistrationPoseRow> ReadRegistrationPoses(const std::filesystem::path& path) {
  std::vector<RegistrationPoseRow> rows;
  std::map<std::pair<int, int>, int> seen;  // (module, counter) -> line
  for (const CsvRow& row : ReadCsv(path, kPosesHeader)) {
    RegistrationPoseRow r;
    r.module = CsvInteger(path, row, 0, "module");
    r.counter = CsvInteger(path, row, 1, "counter");
    if (const auto [it, added] = seen.emplace(std::pair{r.module, r.counter}, row.line); !added) {
      throw FileError(path, fmt::format("line {}: m{} counter {} has a pose already (line {})",
                                        row.line, r.module, r.counter, it->second));
    }
    r.time_s = CsvNumber(path, row, 2, "time_s");
    const Eigen::Vector3d p(CsvNumber(path, row, 3, "x_mm"), CsvNumber(path, row, 4, "y_mm"),
                            CsvNumber(path, row, 5, "z_mm"));
    const Eigen::Quaterniond q(CsvNumber(path, row, 9, "qw"), CsvNumber(path, row, 6, "qx"),
                               CsvNumber(path, row, 7, "qy"), CsvNumber(path, row, 8, "qz"));
    if (std::abs(q.norm() - 1.0) > 1e-6)
      throw FileError(path, "line " + std::to_string(row.line) + ": quaternion not unit");
    r.world_from_camera = Rigid3d(q, p);
    rows.push_back(r);
  }
  return rows;
}

int RegistrationVertexId(int module, int counter) { return module * 1000000 + counter; }

void WriteRegistrationEdges(const std::filesystem::path& path,
                            const std::vector<RegistrationEdgeRow>& rows) {
  std::string text = std::string(kEdgesHeader) + "\n";
  for (const RegistrationEdgeRow& r : rows) {
    text += fmt::format("{},{},{},{},{},{},{},{},{:.6f}",
                        RegistrationVertexId(r.from_module, r.from_counter),
                        RegistrationVertexId(r.to_module, r.to_counter), r.from_module,
                        r.from_counter, r.to_module, r.to_counter, r.type, r.inliers, r.rms_mm);
    for (int k = 0; k < 6; ++k) text += fmt::format(",{:.6g}", r.eigenvalues[k]);
    text += fmt::format(",{:.6g},{}\n", r.chi2, r.accepted ? 1 : 0);
  }
  WriteTextFileAtomically(path, text);
}

std::vector<RegistrationEdgeRow> ReadRegistrationEdges(const std::filesystem::path& path) {
  std::vector<RegistrationEdgeRow> rows;
  for (const CsvRow& row : ReadCsv(path, kEdgesHeader)) {
    RegistrationEdgeRow r;
    r.from_module = CsvInteger(path, row, 2, "from_module");
    r.from_counter = CsvInteger(path, row, 3, "from_counter");
    r.to_module = CsvInteger(path, row, 4, "to_module");
    r.to_counter = CsvInteger(path, row, 5, "to_counter");
    r.type = row.fields[6];
    r.inliers = CsvInteger(path, row, 7, "inliers");
    r.rms_mm = CsvNumber(path, row, 8, "rms_mm");
    for (int k = 0; k < 6; ++k) r.eigenvalues[k] = CsvNumber(path, row, 9 + k, "eig");
    r.chi2 = CsvNumber(path, row, 15, "chi2");
    r.accepted = CsvInteger(path, row, 16, "accepted") != 0;
    rows.push_back(r);
  }
  return rows;
}

std::filesystem::path PairRecordFile(const std::filesystem::path& pairs_folder, int a_module,
                                     int a_counter, int b_module, int b_counter) {
  return pairs_folder /
         fmt::format("m{}_{:06d}-m{}_{:06d}.json", a_module, a_counter, b_module, b_counter);
}

void WritePairRecord(const std::filesystem::path& path, const PairRecord& r) {
  json info = json::array();
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 6; ++k) info.push_back(r.information(i, k));
  const Eigen::Quaterniond& q = r.a_from_b.rotation;
  const Eigen::Vector3d& t = r.a_from_b.translation;
  const json j = {
      {"a", {{"module", r.a_module}, {"counter", r.a_counter}}},
      {"b", {{"module", r.b_module}, {"counter", r.b_counter}}},
      {"kind", r.kind},
      {"method", r.method},
      {"a_from_b", {{"q_xyzw", {q.x(), q.y(), q.z(), q.w()}}, {"t_mm", {t.x(), t.y(), t.z()}}}},
      {"information", info},
      {"inliers", r.inliers},
      {"rms_mm", r.rms_mm},
      {"seconds", r.seconds},
      {"degenerate", r.degenerate},
      {"photometric", r.photometric},
      {"message", r.message}};
  WriteTextFileAtomically(path, j.dump(1) + "\n");
}

std::optional<PairRecord> ReadPairRecord(const std::filesystem::path& path) {
  if (!IsRegularFile(path)) return std::nullopt;
  try {
    const json j = json::parse(ReadTextFile(path));
    PairRecord r;
    r.a_module = j.at("a").at("module");
    r.a_counter = j.at("a").at("counter");
    r.b_module = j.at("b").at("module");
    r.b_counter = j.at("b").at("counter");
    r.kind = j.at("kind");
    r.method = j.at("method");
    r.a_from_b = PoseFromJson(path, j.at("a_from_b"));
    const std::vector<double> info = j.at("information").get<std::vector<double>>();
    if (info.size() != 36) throw FileError(path, "information needs 36 numbers");
    for (int i = 0; i < 36; ++i) r.information(i / 6, i % 6) = info[i];
    r.inliers = j.at("inliers");
    r.rms_mm = j.at("rms_mm");
    r.seconds = j.at("seconds");
    r.degenerate = j.at("degenerate");
    r.photometric = j.value("photometric", false);  // absent in records before 2026-12-05
    r.message = j.at("message");
    return r;
  } catch (const json::exception& e) {
    throw FileError(path,
                    std::string("not a pair record (remove it to redo the pair): ") + e.what());
  }
}

RgbdPairInput ReadRgbdForRegistration(const std::filesystem::path& rgbd_folder, int module,
                                      int counter) {
  const RgbdFiles files = RgbdAcquisitionFiles(rgbd_folder, module, counter);
  // As written: grey (a pattern image put in its place) is no colour to texture the model with.
  const cv::Mat color = ReadImage(files.color, cv::IMREAD_UNCHANGED);
  if (color.type() != CV_8UC3) {
    throw FileError(files.color, "not an 8-bit colour image (" + std::to_string(color.channels()) +
                                     " channel(s) of " + std::to_string(color.elemSize1() * 8) +
                                     " bits): rgbd writes 8-bit RGB; run rgbd --force");
  }
  const cv::Mat1f depth = ReadRgbdDepth(rgbd_folder, module, counter);
  if (color.size() != depth.size())
    throw FileError(files.color, "size differs from the depth map's " + files.depth.string());
  return {cv::Mat3b(color), depth};
}

cv::Mat1f ReadRgbdDepth(const std::filesystem::path& rgbd_folder, int module, int counter) {
  const std::filesystem::path path = RgbdAcquisitionFiles(rgbd_folder, module, counter).depth;
  cv::Mat depth = ReadImage(path, cv::IMREAD_UNCHANGED);
  if (depth.type() != CV_32FC1) throw FileError(path, "not a float32 depth map");
  return depth;
}

void WriteRegistrationGraphPicture(const std::filesystem::path& path,
                                   const std::vector<GraphPictureNode>& nodes,
                                   const std::vector<GraphPictureEdge>& edges) {
  const int width = 1600, height = 700, margin = 60, legend = 40;
  double lo = 0.0, hi = 1.0;
  if (!nodes.empty()) {
    const auto [min_it, max_it] = std::minmax_element(
        nodes.begin(), nodes.end(), [](const GraphPictureNode& x, const GraphPictureNode& y) {
          return x.station_mm < y.station_mm;
        });
    lo = min_it->station_mm - 20.0;
    hi = std::max(max_it->station_mm + 20.0, lo + 1.0);
  }
  auto pixel = [&](const GraphPictureNode& n) {
    const double x = margin + (n.station_mm - lo) / (hi - lo) * (width - 2 * margin);
    const double y = legend + margin + n.clock_h / 12.0 * (height - legend - 2 * margin);
    return cv::Point(static_cast<int>(std::lround(x)), static_cast<int>(std::lround(y)));
  };
  cv::Mat3b image(height, width, cv::Vec3b(255, 255, 255));
  const cv::Scalar colours[5] = {
      {60, 160, 40}, {200, 90, 20}, {0, 140, 255}, {140, 140, 140}, {200, 40, 200}};
  const char* names[5] = {"feature", "projection", "rig", "odometry", "straightness"};
  for (int h = 0; h <= 12; h += 3) {  // clock grid
    const int y = pixel({lo, static_cast<double>(h)}).y;
    cv::line(image, {margin, y}, {width - margin, y}, cv::Scalar(225, 225, 225), 1);
    cv::putText(image, fmt::format("{}h", h == 0 ? 12 : h), {8, y + 5}, cv::FONT_HERSHEY_SIMPLEX,
                0.45, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  const int strip_top = pixel({lo, 0.0}).y, strip_bottom = pixel({lo, 12.0}).y;
  const cv::Rect strip(0, strip_top, width, strip_bottom - strip_top + 1);
  // Priors first, measurements last: the feature and projection edges stay visible where a
  // straightness or odometry edge runs along the same row.
  for (int type = 4; type >= 0; --type) {
    for (const GraphPictureEdge& e : edges) {
      if (e.type != type || e.a < 0 || e.b < 0 || e.a >= static_cast<int>(nodes.size()) ||
          e.b >= static_cast<int>(nodes.size()))
        continue;
      const GraphPictureNode a = OnClockFace(nodes[e.a]), b = OnClockFace(nodes[e.b]);
      const cv::Scalar colour = e.accepted ? colours[e.type] : cv::Scalar(0, 0, 230);
      const int thickness = e.accepted ? 2 : 1;
      if (std::abs(a.clock_h - b.clock_h) <= 6.0) {
        cv::line(image, pixel(a), pixel(b), colour, thickness, cv::LINE_AA);
        continue;
      }
      // Across 12 o'clock the edge leaves the strip at one border and comes back at the other.
      const double turn = a.clock_h > b.clock_h ? 12.0 : -12.0;
      const std::pair<cv::Point, cv::Point> halves[2] = {
          {pixel(a), pixel({b.station_mm, b.clock_h + turn})},
          {pixel({a.station_mm, a.clock_h - turn}), pixel(b)}};
      for (auto [p, q] : halves)
        if (cv::clipLine(strip, p, q)) cv::line(image, p, q, colour, thickness, cv::LINE_AA);
    }
  }
  for (const GraphPictureNode& n : nodes)
    cv::circle(image, pixel(OnClockFace(n)), 3, cv::Scalar(0, 0, 0), -1);
  for (int t = 0; t < 5; ++t) {
    const cv::Point at(margin + 170 * t, 22);
    cv::line(image, at, at + cv::Point(30, 0), colours[t], 3);
    cv::putText(image, names[t], at + cv::Point(36, 5), cv::FONT_HERSHEY_SIMPLEX, 0.5,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  cv::putText(image, fmt::format("station {:.0f} .. {:.0f} mm", lo, hi), {width - 330, 22},
              cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  WriteFileAtomically(
      path, [&](const std::filesystem::path& temporary) { WriteImage(temporary, image); });
}

}  // namespace sewer3d
