// The model evaluation's JSON and its error map picture (model_evaluation.hpp).

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "sewer3d/simeval/model_evaluation.hpp"
#include "sewer3d/simeval/picture.hpp"

namespace sewer3d {
namespace {

// A figure of an empty set is no figure: null, not 0.
nlohmann::json Value(double value, bool measured) {
  return measured ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json FiguresJson(const ErrorFigures& f) {
  const bool any = f.cells > 0;
  return {{"cells", f.cells},
          {"mean_mm", Value(f.mean_mm, any)},
          {"rms_mm", Value(f.rms_mm, any)},
          {"median_abs_mm", Value(f.median_abs_mm, any)},
          {"p95_abs_mm", Value(f.p95_abs_mm, any)},
          {"max_abs_mm", Value(f.max_abs_mm, any)}};
}

/// Mean of the finite values of `error` in cells of `factor` × `factor` (NaN where none).
cv::Mat1f Shrink(const cv::Mat1f& error, double factor) {
  const int rows = std::max(1, static_cast<int>(std::lround(error.rows * factor)));
  const int cols = std::max(1, static_cast<int>(std::lround(error.cols * factor)));
  cv::Mat1f sum(rows, cols, 0.0f), count(rows, cols, 0.0f);
  for (int r = 0; r < error.rows; ++r) {
    const int rr = std::min(rows - 1, static_cast<int>(r * factor));
    for (int c = 0; c < error.cols; ++c) {
      if (!std::isfinite(error(r, c))) continue;
      const int cc = std::min(cols - 1, static_cast<int>(c * factor));
      sum(rr, cc) += error(r, c);
      count(rr, cc) += 1.0f;
    }
  }
  cv::Mat1f mean(rows, cols, std::numeric_limits<float>::quiet_NaN());
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      if (count(r, c) > 0.0f) mean(r, c) = sum(r, c) / count(r, c);
  return mean;
}

/// A round station step so that labels are at least `min_px` apart.
double StationStep(double px_per_mm, double min_px) {
  for (double step : {1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0})
    if (step * px_per_mm >= min_px) return step;
  return 5000.0;
}

}  // namespace

std::string ModelEvaluationToJson(const ModelEvaluation& e) {
  nlohmann::json coverage = nlohmann::json::object(), materials = nlohmann::json::object();
  for (const auto& [name, f] : e.by_coverage) coverage[name] = FiguresJson(f);
  for (const auto& [name, f] : e.by_material) materials[name] = FiguresJson(f);
  nlohmann::json after_axis = nlohmann::json::object();
  for (const auto& [name, f] : e.after_axis_offset_by_material) after_axis[name] = FiguresJson(f);
  nlohmann::json hours = nlohmann::json::array();
  for (size_t h = 0; h < e.by_clock_hour.size(); ++h) {
    nlohmann::json j = FiguresJson(e.by_clock_hour[h]);
    j["from_clock_h"] = h == 0 ? 12 : static_cast<int>(h);
    hours.push_back(j);
  }
  nlohmann::json profile = nlohmann::json::array();
  for (const CircumferenceSample& s : e.circumference_profile)
    profile.push_back(
        {{"station_mm", s.station_mm}, {"model_mm", s.model_mm}, {"truth_mm", s.truth_mm}});
  const CircumferenceFigures& c = e.circumference;
  const Eigen::Vector3d t = e.truth_from_model.translation;
  const Eigen::Quaterniond& q = e.truth_from_model.rotation;
  const nlohmann::json j = {
      {"error", "signed distance of the map point from the true wall, mm, positive outward"},
      {"stride", e.stride},
      {"all", FiguresJson(e.all)},
      {"by_coverage", coverage},
      {"by_material", materials},
      {"by_clock_hour", hours},
      {"axis_offset",
       {{"rows", e.axis_offset.cells},
        {"mean_mm", Value(e.axis_offset.mean_mm, e.axis_offset.cells > 0)},
        {"median_mm", Value(e.axis_offset.median_abs_mm, e.axis_offset.cells > 0)},
        {"p95_mm", Value(e.axis_offset.p95_abs_mm, e.axis_offset.cells > 0)},
        {"max_mm", Value(e.axis_offset.max_abs_mm, e.axis_offset.cells > 0)}}},
      {"after_axis_offset", FiguresJson(e.after_axis_offset)},
      {"clean", FiguresJson(e.clean)},
      {"clean_after_axis_offset", FiguresJson(e.clean_after_axis_offset)},
      {"after_axis_offset_by_material", after_axis},
      {"circumference",
       {{"sections", c.sections},
        {"mean_diff_mm", Value(c.mean_diff_mm, c.sections > 0)},
        {"mean_abs_diff_mm", Value(c.mean_abs_diff_mm, c.sections > 0)},
        {"max_abs_diff_mm", Value(c.max_abs_diff_mm, c.sections > 0)},
        {"profile", profile}}},
      {"truth_from_model",
       {{"translation_mm", {t.x(), t.y(), t.z()}},
        {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}}}}};
  return j.dump(2) + "\n";
}

cv::Mat3b ModelErrorMap(const ModelEvaluation& e, double range_mm, int length_px,
                        bool after_axis_offset) {
  const int stations = std::max(1, e.error_mm.rows);
  const double factor = std::min(1.0, static_cast<double>(length_px) / stations);
  const cv::Mat1f small = Shrink(after_axis_offset ? e.after_axis_offset_mm : e.error_mm, factor);
  const cv::Mat3b map = DisplacementView(small, range_mm).t();  // station along x, crown on top
  const int left = 70, top = 30, right = 130, bottom = 45;
  cv::Mat3b out(map.rows + top + bottom, map.cols + left + right, cv::Vec3b(255, 255, 255));
  map.copyTo(out(cv::Rect(left, top, map.cols, map.rows)));
  DrawLabel(out,
            fmt::format("signed error of the model against the true wall{} (stride {}, +-{:g} mm)",
                        after_axis_offset ? ", each station's axis offset removed," : "", e.stride,
                        range_mm),
            {left, 20});
  // Clock ticks: 12, 3, 6, 9, 12 o'clock down the left side.
  for (int h = 0; h <= 4; ++h) {
    const int y = top + static_cast<int>(std::lround(h * 0.25 * (map.rows - 1)));
    cv::line(out, {left - 6, y}, {left - 1, y}, cv::Scalar(0, 0, 0));
    DrawLabel(out, fmt::format("{}h", h % 4 == 0 ? 12 : 3 * h), {left - 40, y + 5});
  }
  // Station ticks along the bottom (model stations, mm).
  const double mm_per_px = e.grid.resolution_mm * e.stride * stations / map.cols;
  const double step = StationStep(1.0 / mm_per_px, 80.0);
  const double s0 = e.grid.station0_mm, s1 = s0 + e.grid.rows * e.grid.resolution_mm;
  for (double s = std::ceil(s0 / step) * step; s <= s1; s += step) {
    const int x = left + static_cast<int>(std::lround((s - s0) / mm_per_px));
    if (x >= left + map.cols) break;
    cv::line(out, {x, top + map.rows}, {x, top + map.rows + 5}, cv::Scalar(0, 0, 0));
    DrawLabel(out, fmt::format("{:g}", s), {x - 14, top + map.rows + 20});
  }
  DrawLabel(out, "station (mm)", {left + map.cols / 2 - 40, top + map.rows + 38});
  DrawColourBar(out, {left + map.cols + 20, top}, std::min(map.rows, 300), range_mm);
  return out;
}

}  // namespace sewer3d
