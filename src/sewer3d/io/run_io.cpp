#include "sewer3d/io/run_io.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/io/module_io.hpp"
#include "sewer3d/io/scenario_io.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;

// Lines of a CSV file with the expected header; throws naming the line on a wrong field count.
std::vector<std::vector<std::string>> ReadCsv(const std::filesystem::path& path,
                                              const std::string& header) {
  std::istringstream in(ReadTextFile(path));
  std::string line;
  if (!std::getline(in, line) || line != header)
    throw FileError(path, "line 1: header must be '" + header + "'");
  const size_t columns = std::count(header.begin(), header.end(), ',') + 1;
  std::vector<std::vector<std::string>> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
    if (fields.size() != columns) {
      throw FileError(
          path, fmt::format("line {}: {} fields, expected {}", number, fields.size(), columns));
    }
    rows.push_back(std::move(fields));
  }
  return rows;
}

double ToNumber(const std::filesystem::path& path, size_t row, const std::string& text) {
  try {
    size_t used = 0;
    const double x = std::stod(text, &used);
    if (used == text.size() && std::isfinite(x)) return x;
  } catch (const std::exception&) {
  }
  throw FileError(path, fmt::format("line {}: '{}' is not a number", row + 2, text));
}

ImageKind ToKind(const std::filesystem::path& path, size_t row, const std::string& text) {
  for (const auto k : {ImageKind::kTextureBefore, ImageKind::kPattern, ImageKind::kTextureAfter}) {
    if (text == ImageKindName(k)) return k;
  }
  throw FileError(
      path, fmt::format("line {}: image '{}' must be texture_before, pattern or texture_after",
                        row + 2, text));
}

// The columns every per-image file starts with: module, counter, image, time_s.
template <typename Row>
void ReadImageKey(const std::filesystem::path& path, size_t i, const std::vector<std::string>& f,
                  Row& row) {
  row.module = static_cast<int>(ToNumber(path, i, f[0]));
  row.counter = static_cast<int>(ToNumber(path, i, f[1]));
  row.kind = ToKind(path, i, f[2]);
  row.time_s = ToNumber(path, i, f[3]);
}

json PoseJson(const Rigid3d& pose) {
  const Eigen::Matrix3d r = pose.RotationMatrix();
  return {{"rotation",
           {r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)}},
          {"translation_mm", {pose.translation.x(), pose.translation.y(), pose.translation.z()}}};
}

constexpr const char* kIndexHeader = "module,counter,image,time_s,exposure_ms,file";
constexpr const char* kPoseHeader =
    "module,counter,image,time_s,station_mm,x_mm,y_mm,z_mm,qx,qy,qz,qw";

}  // namespace

std::string RigToJson(const Rig& rig) {
  json j;
  j["format"] = "sewer3d-rig";
  j["version"] = 1;
  j["carrier"] = {{"diameter_mm", rig.carrier_diameter_mm}, {"length_mm", rig.carrier_length_mm}};
  j["modules"] = json::array();
  for (const RigModule& m : rig.modules) {
    j["modules"].push_back({{"name", m.name},
                            {"clock_h", m.clock_h},
                            {"module", json::parse(ModuleToJson(m.module))},
                            {"carrier_from_camera", PoseJson(m.carrier_from_camera)}});
  }
  return j.dump(2) + "\n";
}

void WriteRig(const std::filesystem::path& path, const Rig& rig) {
  WriteTextFile(path, RigToJson(rig));
}

LoadedRig ReadRig(const std::filesystem::path& path) {
  const JsonReader in(path);
  const json j = in.ParseObject(ReadTextFile(path));
  if (in.Text(j, "format", "", "") != "sewer3d-rig") in.Fail("format", "must be \"sewer3d-rig\"");
  LoadedRig out;
  const json& carrier = in.Object(j, "carrier", "");
  out.rig.carrier_diameter_mm = in.Number(carrier, "diameter_mm", "carrier.", 150.0);
  out.rig.carrier_length_mm = in.Number(carrier, "length_mm", "carrier.", 600.0);
  const json& modules = in.Array(j, "modules", "");
  if (modules.empty()) in.Fail("modules", "must list at least one module");
  for (size_t i = 0; i < modules.size(); ++i) {
    const std::string p = "modules[" + std::to_string(i) + "].";
    const json& m = modules[i];
    if (!m.is_object() || !m.contains("module") || !m.contains("carrier_from_camera")) {
      in.Fail(p, "must be an object with module and carrier_from_camera");
    }
    RigModule rm;
    rm.name = in.Text(m, "name", p, fmt::format("m{}", i));
    rm.clock_h = in.Number(m, "clock_h", p, 12.0);
    try {
      rm.module = ParseModule(m["module"].dump(), path);
    } catch (const FileError& e) {
      throw FileError(path,
                      p + "module: " + std::string(e.what()).substr(path.string().size() + 2));
    }
    const json& pose = in.Object(m, "carrier_from_camera", p);
    const auto& r = pose.value("rotation", json::array());
    const auto& t = pose.value("translation_mm", json::array());
    if (r.size() != 9 || t.size() != 3)
      in.Fail(p + "carrier_from_camera", "needs rotation[9] and translation_mm[3]");
    Eigen::Matrix3d rot;
    Eigen::Vector3d tr;
    for (int k = 0; k < 9; ++k) {
      if (!r[k].is_number()) in.Fail(p + "carrier_from_camera.rotation", "must hold numbers");
      rot(k / 3, k % 3) = r[k].get<double>();
    }
    for (int k = 0; k < 3; ++k) {
      if (!t[k].is_number()) in.Fail(p + "carrier_from_camera.translation_mm", "must hold numbers");
      tr[k] = t[k].get<double>();
    }
    if ((rot.transpose() * rot - Eigen::Matrix3d::Identity()).norm() > 1e-6 ||
        rot.determinant() < 0.0) {
      in.Fail(p + "carrier_from_camera.rotation", "is not a rotation");
    }
    rm.carrier_from_camera = Rigid3d(rot, tr);
    std::filesystem::path matrix = rm.module.pattern.matrix_path;
    if (matrix.is_relative()) matrix = path.parent_path() / matrix;
    out.patterns.push_back(ReadPatternMatrix(matrix));
    out.rig.modules.push_back(rm);
  }
  ValidateFileContents(path, [&] { out.rig.Check(); });
  return out;
}

void WriteIndex(const std::filesystem::path& path, const std::vector<IndexEntry>& entries) {
  std::string text = std::string(kIndexHeader) + "\n";
  for (const IndexEntry& e : entries) {
    text += fmt::format("{},{},{},{:.6f},{:.3f},{}\n", e.module, e.counter, ImageKindName(e.kind),
                        e.time_s, e.exposure_ms, e.file);
  }
  WriteTextFile(path, text);
}

std::vector<IndexEntry> ReadIndex(const std::filesystem::path& path) {
  std::vector<IndexEntry> out;
  const auto rows = ReadCsv(path, kIndexHeader);
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& f = rows[i];
    IndexEntry e;
    ReadImageKey(path, i, f, e);
    e.exposure_ms = ToNumber(path, i, f[4]);
    e.file = f[5];
    out.push_back(e);
  }
  return out;
}

void WriteOdometry(const std::filesystem::path& path, const std::vector<OdometrySample>& samples) {
  std::string text = "time_s,distance_mm\n";
  for (const auto& s : samples) text += fmt::format("{:.6f},{:.4f}\n", s.time_s, s.measured_mm);
  WriteTextFile(path, text);
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
  const auto rows = ReadCsv(path, kPoseHeader);
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& f = rows[i];
    TruthPose p;
    ReadImageKey(path, i, f, p);
    p.station_mm = ToNumber(path, i, f[4]);
    const Eigen::Vector3d t(ToNumber(path, i, f[5]), ToNumber(path, i, f[6]),
                            ToNumber(path, i, f[7]));
    const Eigen::Quaterniond q(ToNumber(path, i, f[11]), ToNumber(path, i, f[8]),
                               ToNumber(path, i, f[9]), ToNumber(path, i, f[10]));
    if (std::abs(q.norm() - 1.0) > 1e-6)
      throw FileError(path, fmt::format("line {}: quaternion not unit", i + 2));
    p.world_from_carrier = Rigid3d(q, t);
    out.push_back(p);
  }
  return out;
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
