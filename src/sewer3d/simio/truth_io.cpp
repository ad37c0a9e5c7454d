#include "sewer3d/simio/truth_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "sewer3d/io/csv.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/simio/scenario_io.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;

constexpr const char* kPoseHeader =
    "module,counter,image,time_s,station_mm,x_mm,y_mm,z_mm,qx,qy,qz,qw";

// sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1].
double LinearToSrgb(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

}  // namespace

void WriteCameraGains(const std::filesystem::path& path,
                      const std::vector<Eigen::Vector3d>& gains_rgb) {
  std::string text = "module,gain_r,gain_g,gain_b\n";
  for (size_t m = 0; m < gains_rgb.size(); ++m) {
    text += fmt::format("{},{:.6f},{:.6f},{:.6f}\n", m, gains_rgb[m].x(), gains_rgb[m].y(),
                        gains_rgb[m].z());
  }
  WriteTextFile(path, text);
}

std::vector<std::filesystem::path> TruthAlbedoFiles(const std::filesystem::path& path_stem) {
  const std::string stem = path_stem.string();
  return {stem + ".png", stem + "_linear.png"};
}

void WriteTruthAlbedo(const std::filesystem::path& path_stem, const cv::Mat3f& albedo_rgb) {
  cv::Mat3b srgb(albedo_rgb.size());
  cv::Mat3w linear(albedo_rgb.size());
  for (int v = 0; v < albedo_rgb.rows; ++v) {
    for (int u = 0; u < albedo_rgb.cols; ++u) {
      for (int c = 0; c < 3; ++c) {
        const float a = albedo_rgb(v, u)[c];
        const double x = std::isnan(a) ? 0.0 : std::clamp(static_cast<double>(a), 0.0, 1.0);
        srgb(v, u)[2 - c] = static_cast<std::uint8_t>(std::lround(255.0 * LinearToSrgb(x)));
        linear(v, u)[2 - c] = static_cast<std::uint16_t>(std::lround(65535.0 * x));
      }
    }
  }
  const std::vector<std::filesystem::path> files = TruthAlbedoFiles(path_stem);
  WriteImage(files[0], srgb);
  WriteImage(files[1], linear);
}

void WriteOdometryTruth(const std::filesystem::path& path,
                        const std::vector<OdometrySample>& samples) {
  std::string text = "time_s,true_mm,scale_mm,slip_mm,noise_mm,measured_mm\n";
  for (const auto& s : samples) {
    text += fmt::format("{:.6f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}\n", s.time_s, s.true_mm,
                        s.scale_mm, s.slip_mm, s.noise_mm, s.measured_mm);
  }
  WriteTextFile(path, text);
}

void WriteTruthPoses(const std::filesystem::path& path, const std::vector<TruthPose>& poses) {
  std::string text = std::string(kPoseHeader) + "\n";
  for (const TruthPose& p : poses) {
    const Eigen::Vector3d& t = p.world_from_carrier.translation;
    const Eigen::Quaterniond& q = p.world_from_carrier.rotation;
    text +=
        fmt::format("{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.12f},{:.12f},{:.12f},{:.12f}\n",
                    p.module, p.counter, ImageKindName(p.kind), p.time_s, p.station_mm, t.x(),
                    t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
  }
  WriteTextFile(path, text);
}

std::vector<TruthPose> ReadTruthPoses(const std::filesystem::path& path) {
  std::vector<TruthPose> out;
  for (const CsvRow& row : ReadCsv(path, kPoseHeader)) {
    TruthPose p;
    ReadImageKey(path, row, p);
    const auto x = [&](size_t c) { return CsvNumber(path, row, c, "pose"); };
    p.station_mm = CsvNumber(path, row, 4, "station_mm");
    const Eigen::Vector3d t(x(5), x(6), x(7));
    const Eigen::Quaterniond q(x(11), x(8), x(9), x(10));
    if (std::abs(q.norm() - 1.0) > 1e-6)
      throw FileError(path, fmt::format("line {}: quaternion not unit", row.line));
    p.world_from_carrier = Rigid3d(q, t);
    out.push_back(p);
  }
  return out;
}

std::vector<TruthPose> ReadTruthPoses(const std::filesystem::path& path, std::size_t images) {
  std::vector<TruthPose> poses = ReadTruthPoses(path);
  if (poses.size() != images) {
    throw FileError(path, fmt::format("holds {} poses, but the run's acquisitions.csv lists {} "
                                      "images (one pose each): the truth is cut short or of "
                                      "another run",
                                      poses.size(), images));
  }
  return poses;
}

void WriteCalibrationTruth(const std::filesystem::path& path, const CalibrationTruth& truth) {
  json j;
  j["board"] = {
      {"cols", truth.board.cols}, {"rows", truth.board.rows}, {"square_mm", truth.board.square_mm}};
  j["realism"] = truth.realism;
  j["poses"] = json::array();
  for (const Rigid3d& pose : truth.camera_from_board)
    j["poses"].push_back({{"camera_from_board", PoseToJson(pose)}});
  WriteTextFile(path, j.dump(2) + "\n");
}

CalibrationTruth ReadCalibrationTruth(const std::filesystem::path& path) {
  const JsonReader in(path);
  const json j = in.ParseObject(ReadTextFile(path));
  CalibrationTruth truth;
  const json& board = in.RequiredObject(j, "board", "");
  truth.board.cols = in.Integer(board, "cols", "board.", truth.board.cols);
  truth.board.rows = in.Integer(board, "rows", "board.", truth.board.rows);
  truth.board.square_mm = in.Positive(board, "square_mm", "board.");
  ValidateFileContents(path, [&] { truth.board.Check(); });
  truth.realism = in.Text(j, "realism", "", truth.realism);
  if (truth.realism != "ideal" && truth.realism != "paper")
    in.Fail("realism", "must be ideal or paper, got " + truth.realism);
  const json& poses = in.Array(j, "poses", "");
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (!poses[i].is_object()) in.Fail(fmt::format("poses[{}]", i), "must be an object");
    truth.camera_from_board.push_back(
        in.Pose(poses[i], "camera_from_board", fmt::format("poses[{}].", i)));
  }
  if (truth.camera_from_board.empty()) in.Fail("poses", "holds no pose");
  return truth;
}

void WriteFeatureTruth(const std::filesystem::path& path, const PipeGeometry& pipe) {
  const PipeWorld& w = pipe.world();
  json list = json::array();
  auto dn_at = [&](double station) {
    for (size_t i = w.sections.size(); i-- > 0;) {
      if (station >= pipe.SectionStartMm(static_cast<int>(i))) return w.sections[i].diameter_mm;
    }
    return w.sections.front().diameter_mm;
  };
  for (size_t i = 0; i < w.joints.size(); ++i) {
    const PipeJoint& j = w.joints[i];
    const double station = pipe.SectionStartMm(static_cast<int>(i + 1));
    list.push_back({{"id", j.id},
                    {"type", "joint"},
                    {"code", "BAJ"},
                    {"station_mm", station},
                    {"clock_h", j.offset_clock_h},
                    {"gap_mm", j.gap_mm},
                    {"gap_depth_mm", j.gap_depth_mm},
                    {"offset_mm", j.offset_mm},
                    {"deflection_deg", j.deflection_deg},
                    {"deflection_clock_h", j.deflection_clock_h}});
  }
  for (size_t i = 0; i < w.sections.size(); ++i) {
    const PipeSection& s = w.sections[i];
    if (s.ovality_pct <= 0.0) continue;
    list.push_back({{"id", fmt::format("D{}", i + 1)},
                    {"type", "deformation"},
                    {"code", "BAA"},
                    {"station_mm", pipe.SectionStartMm(static_cast<int>(i))},
                    {"length_mm", s.length_mm},
                    {"clock_h", s.ovality_clock_h},
                    {"deformation_pct", s.ovality_pct}});
  }
  for (const PipeFeature& f : w.features) {
    PipeWorld one;
    one.features = {f};
    json o = json::parse(PipeWorldToJson(one))["features"][0];
    const double dn = dn_at(f.station_mm);
    switch (f.type) {
      case PipeFeature::Type::kConnection:
        o["code"] = "BAG";
        o["intrusion_pct_of_dn"] = 100.0 * f.intrusion_mm / dn;
        break;
      case PipeFeature::Type::kSpalling:
        o["code"] = "BAF";
        break;
      case PipeFeature::Type::kCrack:
        o["code"] = "BAB";
        break;
      case PipeFeature::Type::kWet:
        o["code"] = "BBF";  // infiltration; a wet patch is its first grade, seeping (A)
        break;
      case PipeFeature::Type::kDeposit: {
        // Share of the cross-section the deposit fills: the circular segment of height h.
        const double r = 0.5 * dn, h = f.height_mm, theta = 2.0 * std::acos((r - h) / r);
        o["code"] = "BBC";
        o["cross_section_loss_pct"] = 100.0 * (theta - std::sin(theta)) / (2.0 * std::numbers::pi);
        break;
      }
      case PipeFeature::Type::kBump:
      case PipeFeature::Type::kPit:
      case PipeFeature::Type::kJointStep:
        break;  // pipe-wall scene kinds, which PipeWorld::Check keeps out of a pipe world
    }
    list.push_back(o);
  }
  WriteTextFile(
      path,
      json{{"format", "sewer3d-features"}, {"version", 1}, {"features", list}}.dump(2) + "\n");
}

}  // namespace sewer3d
