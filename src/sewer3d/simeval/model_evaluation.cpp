#include "sewer3d/simeval/model_evaluation.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/simeval/profile_evaluation.hpp"
#include "sewer3d/simeval/truth_alignment.hpp"
#include "sewer3d/simio/render_json.hpp"
#include "sewer3d/simio/scenario_io.hpp"

namespace sewer3d {

void ModelEvaluationOptions::Check() const {
  ValidateNotNegative("stride", stride);
  ValidatePositive("target_cells", static_cast<double>(target_cells));
  SEWER3D_VALIDATE(max_cells >= target_cells, "max_cells",
                   "must be at least target_cells (" << target_cells << "), got " << max_cells);
  ValidatePositive("station_bin_mm", station_bin_mm);
  ValidateNotNegative("clean_margin_mm", clean_margin_mm);
  ValidatePositive("axis_outlier_mm", axis_outlier_mm);
  SEWER3D_VALIDATE(circumference_directions >= 8, "circumference_directions",
                   "must be ≥ 8, got " << circumference_directions);
  ValidateNotNegative("circumference_half_band_mm", circumference_half_band_mm);
}

namespace {

ErrorFigures Figures(std::vector<float> errors) {
  ErrorFigures f;
  f.cells = static_cast<std::int64_t>(errors.size());
  if (errors.empty()) return f;
  double sum = 0.0, sum2 = 0.0;
  for (float& e : errors) {
    sum += e;
    sum2 += static_cast<double>(e) * e;
    e = std::abs(e);
  }
  const auto n = static_cast<double>(errors.size());
  f.mean_mm = sum / n;
  f.rms_mm = std::sqrt(sum2 / n);
  auto quantile = [&errors](double q) {
    const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(errors.size() - 1));
    std::nth_element(errors.begin(), errors.begin() + k, errors.end());
    return static_cast<double>(errors[static_cast<size_t>(k)]);
  };
  f.median_abs_mm = quantile(0.5);
  f.p95_abs_mm = quantile(0.95);
  f.max_abs_mm = *std::max_element(errors.begin(), errors.end());
  return f;
}

struct RowCell {
  int j = 0;  ///< evaluated column
  Material material = Material::kConcrete;
  float error_mm = 0.0f;
  bool clean = false;  ///< away from joints and features
};

/// The first harmonic (a, b) of a row's errors around the clock, e ≈ c + a cos θ + b sin θ: the
/// lateral offset of the model's axis from the true one at that station (crown and 3 o'clock
/// components). Cells beyond ±outlier_mm (joint gaps) are left out of the fit; none when fewer
/// than half the row's cells are left or they do not go round the pipe.
std::optional<Eigen::Vector2d> AxisOffset(const std::vector<RowCell>& cells, int row_cells,
                                          const std::vector<double>& cos_c,
                                          const std::vector<double>& sin_c, double outlier_mm) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  int n = 0;
  for (const RowCell& cell : cells) {
    if (std::abs(cell.error_mm) > outlier_mm) continue;
    const Eigen::Vector3d x(1.0, cos_c[cell.j], sin_c[cell.j]);
    normal += x * x.transpose();
    rhs += x * cell.error_mm;
    ++n;
  }
  if (2 * n < row_cells) return std::nullopt;
  // A full turn gives diag(n, n/2, n/2); a covered arc much shorter than the turn does not.
  if (Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(normal).eigenvalues()[0] < 0.1 * n)
    return std::nullopt;
  const Eigen::Vector3d c = normal.ldlt().solve(rhs);
  return Eigen::Vector2d(c[1], c[2]);
}

int AutomaticStride(const PipeMaps& maps, std::int64_t target_cells) {
  const auto covered = static_cast<double>(cv::countNonZero(maps.coverage));
  return std::max(1, static_cast<int>(std::ceil(std::sqrt(covered / target_cells))));
}

/// The stride asked for, or the automatic one; refuses one that evaluates more than max_cells.
int ChooseStride(const PipeMaps& maps, const ModelEvaluationOptions& options) {
  if (options.stride == 0) return AutomaticStride(maps, options.target_cells);
  const auto covered = static_cast<double>(cv::countNonZero(maps.coverage));
  const double cells = covered / (static_cast<double>(options.stride) * options.stride);
  SEWER3D_VALIDATE(
      cells <= static_cast<double>(options.max_cells), "stride",
      options.stride << " evaluates " << std::llround(cells / 1e6)
                     << " M cells of the map, more than " << options.max_cells / 1'000'000
                     << " M (about 1 GB of error buffers); use a stride of at least "
                     << AutomaticStride(maps, options.max_cells) << ", or 0 (automatic)");
  return options.stride;
}

/// Perimeter of the closed polygon of radii r[k] at clock angles a[k] (one plane).
double Perimeter(const std::vector<double>& r, const std::vector<double>& a) {
  double sum = 0.0;
  for (size_t k = 0; k < r.size(); ++k) {
    const size_t l = (k + 1) % r.size();
    sum += std::hypot(r[l] * std::cos(a[l]) - r[k] * std::cos(a[k]),
                      r[l] * std::sin(a[l]) - r[k] * std::sin(a[k]));
  }
  return sum;
}

/// The model's mean radius over the cells of one sector of the ring: columns [col0, col1) (wrapping
/// around the clock) of rows [row0, row1]; nullopt where fewer than 90 % of them are covered (a
/// joint's gap, a hole).
std::optional<double> SectorRadius(const PipeModel& model, int row0, int row1, int col0, int col1) {
  const PipeMaps& maps = model.maps;
  double sum = 0.0;
  int n = 0, cells = 0;
  for (int r = std::max(0, row0); r <= std::min(maps.grid.rows - 1, row1); ++r) {
    for (int c = col0; c < col1; ++c, ++cells) {
      const int cc = c % maps.grid.cols;
      const float d = maps.displacement_mm(r, cc);
      if (maps.coverage(r, cc) == 0 || !std::isfinite(d)) continue;
      sum += d;
      ++n;
    }
  }
  if (n == 0 || n < 0.9 * cells) return std::nullopt;
  return model.info.centreline.radius_mm + sum / n;
}

/// The cross-section at `row` when the model covers it all around and the true wall is found in
/// every direction. Like a profile ring (inspect/profile.hpp), the wall is averaged over each
/// direction's sector and ±`half_band_mm` of station, the model's cells and the true wall's
/// rays alike (3 stations × 3 clocks per sector), so per-cell noise does not lengthen the
/// perimeter and both sides see the same relief.
std::optional<CircumferenceSample> CrossSection(const PipeModel& model, const PipeGeometry& truth,
                                                const Rigid3d& truth_from_model, int row,
                                                int directions, double half_band_mm) {
  const PipeMaps& maps = model.maps;
  const Centreline& axis = model.info.centreline;
  const double station = maps.grid.RowStationMm(row);
  const int half_rows = static_cast<int>(std::floor(half_band_mm / maps.grid.resolution_mm));
  std::vector<double> clock(directions), r_model(directions), r_true(directions, 0.0);
  const double sector = 2.0 * std::numbers::pi / directions;
  // The true wall's rays start on the axis at three stations across the band.
  std::array<AxisFrame, 3> frames;
  std::array<Eigen::Vector3d, 3> origins;
  for (int i = 0; i < 3; ++i) {
    frames[i] = axis.FrameAt(station + (i - 1) * half_band_mm);
    origins[i] = truth_from_model * frames[i].origin;
  }
  for (int k = 0; k < directions; ++k) {
    const auto col0 = static_cast<int>(static_cast<std::int64_t>(k) * maps.grid.cols / directions);
    const auto col1 =
        static_cast<int>(static_cast<std::int64_t>(k + 1) * maps.grid.cols / directions);
    const std::optional<double> r =
        SectorRadius(model, row - half_rows, row + half_rows, col0, std::max(col1, col0 + 1));
    if (!r) return std::nullopt;
    clock[k] = (k + 0.5) * sector;
    r_model[k] = *r;
    for (int i = 0; i < 3; ++i) {
      for (const double dc : {-sector / 3.0, 0.0, sector / 3.0}) {
        const auto hit = truth.Intersect(
            origins[i], truth_from_model.rotation * frames[i].Direction(clock[k] + dc));
        if (!hit) return std::nullopt;
        r_true[k] += hit->t / 9.0;
      }
    }
  }
  return CircumferenceSample{station, Perimeter(r_model, clock), Perimeter(r_true, clock)};
}

void EvaluateCircumference(const PipeModel& model, const PipeGeometry& truth,
                           const Rigid3d& truth_from_model, const ModelEvaluationOptions& o,
                           ModelEvaluation& e) {
  const MapGrid& grid = model.maps.grid;
  const double length = grid.rows * grid.resolution_mm;
  const int bins = static_cast<int>(std::floor(length / o.station_bin_mm));
  CircumferenceFigures& f = e.circumference;
  for (int b = 0; b < bins; ++b) {
    const int row = static_cast<int>((b + 0.5) * o.station_bin_mm / grid.resolution_mm);
    if (row >= grid.rows) break;
    const auto sample = CrossSection(model, truth, truth_from_model, row,
                                     o.circumference_directions, o.circumference_half_band_mm);
    if (!sample) continue;
    e.circumference_profile.push_back(*sample);
    const double diff = sample->model_mm - sample->truth_mm;
    ++f.sections;
    f.mean_diff_mm += diff;
    f.mean_abs_diff_mm += std::abs(diff);
    f.max_abs_diff_mm = std::max(f.max_abs_diff_mm, std::abs(diff));
  }
  if (f.sections > 0) {
    f.mean_diff_mm /= f.sections;
    f.mean_abs_diff_mm /= f.sections;
  }
}

}  // namespace

ModelEvaluation EvaluatePipeModel(const PipeModel& model, const PipeGeometry& truth,
                                  const Rigid3d& truth_from_model,
                                  const ModelEvaluationOptions& options) {
  options.Check();
  const PipeMaps& maps = model.maps;
  const MapGrid& grid = maps.grid;
  ModelEvaluation e;
  e.grid = grid;
  e.truth_from_model = truth_from_model;
  e.stride = ChooseStride(maps, options);
  const int s = e.stride, first = s / 2;
  const int out_rows = grid.rows > first ? (grid.rows - first + s - 1) / s : 0;
  const int out_cols = grid.cols > first ? (grid.cols - first + s - 1) / s : 0;
  e.error_mm = cv::Mat1f(out_rows, out_cols, std::numeric_limits<float>::quiet_NaN());
  e.after_axis_offset_mm = e.error_mm.clone();

  std::vector<double> cos_c(out_cols), sin_c(out_cols);
  std::vector<int> hour_c(out_cols);
  for (int j = 0; j < out_cols; ++j) {
    const double a = grid.ColClockRad(first + j * s);
    cos_c[j] = std::cos(a);
    sin_c[j] = std::sin(a);
    hour_c[j] = std::min(11, static_cast<int>(a / kTwoPi * 12.0));
  }
  std::vector<float> all;
  std::array<std::vector<float>, 3> by_coverage;
  std::map<Material, std::vector<float>> by_material;
  std::array<std::vector<float>, 12> by_hour;
  std::vector<float> after_axis, axis_offsets, clean, clean_after_axis;
  std::map<Material, std::vector<float>> after_axis_by_material;
  std::vector<RowCell> row_cells;
  const double radius = model.info.centreline.radius_mm;
  const Eigen::Matrix3d rotation = truth_from_model.RotationMatrix();
  for (int i = 0; i < out_rows; ++i) {
    const int row = first + i * s;
    const AxisFrame f = model.info.centreline.FrameAt(grid.RowStationMm(row));
    const Eigen::Vector3d origin = truth_from_model * f.origin;
    const Eigen::Vector3d crown = rotation * f.crown, right = rotation * f.right;
    row_cells.clear();
    for (int j = 0; j < out_cols; ++j) {
      const int col = first + j * s;
      const unsigned char coverage = maps.coverage(row, col);
      const float d = maps.displacement_mm(row, col);
      if (coverage == 0 || coverage > 2 || !std::isfinite(d)) continue;
      const Eigen::Vector3d p_world = origin + (radius + d) * (cos_c[j] * crown + sin_c[j] * right);
      const PipeLocation at = truth.Locate(p_world);
      const auto error = static_cast<float>(at.rho_mm - truth.WallRadiusMm(at));
      e.error_mm(i, j) = error;
      all.push_back(error);
      by_coverage[coverage].push_back(error);
      by_material[truth.world().sections[at.section].material].push_back(error);
      by_hour[hour_c[j]].push_back(error);
      const bool away = IsCleanStation(truth, at.station_mm, options.clean_margin_mm);
      if (away) clean.push_back(error);
      row_cells.push_back({j, truth.world().sections[at.section].material, error, away});
    }
    const auto offset = AxisOffset(row_cells, out_cols, cos_c, sin_c, options.axis_outlier_mm);
    if (!offset) continue;
    axis_offsets.push_back(static_cast<float>(offset->norm()));
    for (const RowCell& cell : row_cells) {
      const auto residual = static_cast<float>(cell.error_mm - (*offset)[0] * cos_c[cell.j] -
                                               (*offset)[1] * sin_c[cell.j]);
      e.after_axis_offset_mm(i, cell.j) = residual;
      after_axis.push_back(residual);
      after_axis_by_material[cell.material].push_back(residual);
      if (cell.clean) clean_after_axis.push_back(residual);
    }
  }
  e.axis_offset = Figures(std::move(axis_offsets));
  e.after_axis_offset = Figures(std::move(after_axis));
  e.clean = Figures(std::move(clean));
  e.clean_after_axis_offset = Figures(std::move(clean_after_axis));
  for (auto& [material, list] : after_axis_by_material)
    e.after_axis_offset_by_material[MaterialName(material)] = Figures(std::move(list));
  e.all = Figures(std::move(all));
  if (!by_coverage[1].empty()) e.by_coverage["measured"] = Figures(std::move(by_coverage[1]));
  if (!by_coverage[2].empty()) e.by_coverage["filled"] = Figures(std::move(by_coverage[2]));
  for (auto& [material, list] : by_material)
    e.by_material[MaterialName(material)] = Figures(std::move(list));
  for (auto& list : by_hour) e.by_clock_hour.push_back(Figures(std::move(list)));
  EvaluateCircumference(model, truth, truth_from_model, options, e);
  return e;
}

ModelEvaluation EvaluateModel(const std::filesystem::path& run_folder,
                              const std::filesystem::path& workspace,
                              const ModelEvaluationOptions& options) {
  options.Check();
  const std::filesystem::path model_json = workspace / "model" / "model.json";
  if (!std::filesystem::exists(model_json))
    throw FileError(model_json, "missing: run the model stage first");
  const CaptureRun run = LoadRun(run_folder);
  const TruthAlignment alignment = AlignRegistrationToTruth(run, run_folder, workspace);
  const PipeGeometry truth(ReadScenario(run_folder / "truth" / "scenario.json").world);
  const PipeModel model = ReadPipeModel(workspace / "model");
  return EvaluatePipeModel(model, truth, alignment.truth_from_model, options);
}

}  // namespace sewer3d
