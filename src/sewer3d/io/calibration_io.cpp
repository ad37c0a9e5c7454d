#include "sewer3d/io/calibration_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {

void WriteCameraCalibration(const std::filesystem::path& path, const CameraCalibrationFile& f) {
  const CalibrationResult& r = f.result;
  nlohmann::json j;
  j["camera"] = IntrinsicsJson(r.intrinsics);
  j["rms_px"] = r.rms_px;
  j["sigma"] = {{"fx", r.sigma[0]},
                {"fy", r.sigma[1]},
                {"cx", r.sigma[2]},
                {"cy", r.sigma[3]},
                {"k", {r.sigma[4], r.sigma[5], r.sigma[6]}}};
  j["views"] = nlohmann::json::array();
  for (size_t v = 0; v < f.images.size(); ++v)
    j["views"].push_back({{"image", f.images[v]}, {"rms_px", r.view_rms_px[v]}});
  j["skipped"] = f.skipped;
  j["board"] = {{"cols", f.board_cols}, {"rows", f.board_rows}, {"square_mm", f.square_mm}};
  j["iterations"] = r.iterations;
  j["converged"] = r.converged;
  WriteTextFile(path, j.dump(2) + "\n");
}

void WriteCornerErrorImage(const std::filesystem::path& path, const cv::Mat& grey,
                           const std::vector<Eigen::Vector2d>& corners,
                           const std::vector<Eigen::Vector2d>& residuals, double rms_px) {
  cv::Mat picture;
  cv::cvtColor(grey, picture, cv::COLOR_GRAY2BGR);
  const double full = std::max(1e-9, 3.0 * rms_px);
  for (size_t i = 0; i < corners.size(); ++i) {
    const double t = std::min(1.0, residuals[i].norm() / full);
    const cv::Scalar colour(0, 255 * (1.0 - t), 255 * t);  // BGR: green to red
    const cv::Point2d p(corners[i].x(), corners[i].y());
    cv::circle(picture, p, 4, colour, cv::FILLED, cv::LINE_AA);
    cv::line(picture, p, p + 20.0 * cv::Point2d(residuals[i].x(), residuals[i].y()), colour, 1,
             cv::LINE_AA);
  }
  cv::putText(picture, cv::format("RMS %.3f px (red: >= %.2f px)", rms_px, full), {8, 20},
              cv::FONT_HERSHEY_SIMPLEX, 0.6, {0, 255, 255}, 1, cv::LINE_AA);
  WriteImage(path, picture);
}

namespace {

// The order of ModuleCalibrationResult::sigma: (object, member) of each.
constexpr std::array<std::pair<const char*, const char*>, 10> kSigmaMembers{{{"camera", "fx"},
                                                                             {"camera", "fy"},
                                                                             {"camera", "cx"},
                                                                             {"camera", "cy"},
                                                                             {"projector", "fx"},
                                                                             {"projector", "fy"},
                                                                             {"projector", "cx"},
                                                                             {"projector", "cy"},
                                                                             {"", "baseline_mm"},
                                                                             {"", "rotation_deg"}}};

}  // namespace

std::string ModuleCalibrationMember(const ModuleCalibrationResult& r, int poses_used, int poses) {
  nlohmann::json sigma = nlohmann::json::object();
  for (std::size_t i = 0; i < kSigmaMembers.size(); ++i) {
    const auto [object, member] = kSigmaMembers[i];
    if (*object == '\0')
      sigma[member] = r.sigma[i];
    else
      sigma[object][member] = r.sigma[i];
  }
  const nlohmann::json calibration = {
      {"poses_used", poses_used},
      {"poses", poses},
      {"rms_px", {{"camera", r.camera_rms_px}, {"projector", r.projector_rms_px}}},
      {"sigma", sigma}};
  return nlohmann::json{{"calibration", calibration}}.dump();
}

std::optional<std::array<double, 10>> ModuleCalibrationSigma(
    const ModuleDescription& module, const std::filesystem::path& module_file) {
  if (module.source_json.empty()) return std::nullopt;
  const JsonReader in(module_file);
  const auto j = in.ParseObject(module.source_json);
  if (!j.contains("calibration")) return std::nullopt;
  const auto& sigma =
      in.RequiredObject(in.RequiredObject(j, "calibration", ""), "sigma", "calibration.");
  std::array<double, 10> out{};
  for (std::size_t i = 0; i < kSigmaMembers.size(); ++i) {
    const auto [object, member] = kSigmaMembers[i];
    const std::string prefix =
        fmt::format("calibration.sigma.{}", *object ? std::string(object) + "." : "");
    const auto& holder = *object ? in.RequiredObject(sigma, object, "calibration.sigma.") : sigma;
    out[i] = in.Number(holder, member, prefix);
    if (!(out[i] >= 0.0)) in.Fail(prefix + member, "must be a standard deviation (>= 0)");
  }
  return out;
}

BoardLayout ReadBoardLayout(const std::filesystem::path& file, const BoardLayout& fallback) {
  const JsonReader in(file);
  const auto j = in.ParseObject(ReadTextFile(file));
  BoardLayout layout;
  layout.square_mm = in.Number(j, "square_mm", "", fallback.square_mm);
  layout.cols = in.Integer(j, "cols", "", fallback.cols);
  layout.rows = in.Integer(j, "rows", "", fallback.rows);
  ValidateFileContents(file, [&] { layout.Check(); });
  return layout;
}

}  // namespace sewer3d
