#include "sewer3d/simeval/profile_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

void ProfileEvaluationOptions::Check() const {
  ValidateNotNegative("clean_margin_mm", clean_margin_mm);
  SEWER3D_VALIDATE(ring_directions >= 8, "ring_directions", "must be ≥ 8, got " << ring_directions);
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

AbsErrorSummary Summarise(std::vector<double> errors) {
  AbsErrorSummary s;
  for (double& e : errors) e = std::abs(e);
  s.rows = static_cast<int>(errors.size());
  if (errors.empty()) return s;
  auto quantile = [&errors](double q) {
    const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(errors.size() - 1));
    std::nth_element(errors.begin(), errors.begin() + k, errors.end());
    return errors[static_cast<size_t>(k)];
  };
  s.median = quantile(0.5);
  s.p95 = quantile(0.95);
  s.max = *std::max_element(errors.begin(), errors.end());
  return s;
}

}  // namespace

std::optional<std::vector<double>> TrueRing(const PipeGeometry& truth, const Centreline& centreline,
                                            const Rigid3d& truth_from_model, double station_mm,
                                            int directions) {
  const AxisFrame frame = centreline.FrameAt(station_mm);
  const Eigen::Vector3d origin = truth_from_model * frame.origin;
  std::vector<double> radius(static_cast<size_t>(directions));
  for (int k = 0; k < directions; ++k) {
    const double clock = (k + 0.5) * 2.0 * std::numbers::pi / directions;
    const auto hit = truth.Intersect(origin, truth_from_model.rotation * frame.Direction(clock));
    if (!hit) return std::nullopt;
    radius[static_cast<size_t>(k)] = hit->t;
  }
  return radius;
}

bool IsCleanStation(const PipeGeometry& truth, double true_station_mm, double margin_mm) {
  const PipeWorld& world = truth.world();
  for (size_t i = 1; i < world.sections.size(); ++i) {
    const double joint = truth.SectionStartMm(static_cast<int>(i));
    const double half_gap = 0.5 * world.joints[i - 1].gap_mm;
    if (std::abs(true_station_mm - joint) <= half_gap + margin_mm) return false;
  }
  for (const PipeFeature& f : world.features) {
    if (f.type == PipeFeature::Type::kWet) continue;  // a film leaves the wall's shape alone
    // A deposit runs from its station over its length; the others reach both ways.
    const bool deposit = f.type == PipeFeature::Type::kDeposit;
    const double from = deposit ? f.station_mm : f.station_mm - PipeFeatureReachMm(f);
    const double to = f.station_mm + PipeFeatureReachMm(f);
    if (true_station_mm >= from - margin_mm && true_station_mm <= to + margin_mm) return false;
  }
  return true;
}

ProfileEvaluation EvaluateProfileAgainstTruth(const Profile& profile, const Centreline& centreline,
                                              const PipeGeometry& truth,
                                              const Rigid3d& truth_from_model,
                                              const ProfileOptions& profile_options,
                                              const ProfileEvaluationOptions& options) {
  profile_options.Check();
  options.Check();
  ProfileEvaluation e;
  std::vector<double> circumference, mean_diameter, ovality_en, ovality_astm, height, width;
  for (const ProfileRow& row : profile.rows) {
    ProfileRowEvaluation r;
    r.station_mm = row.station_mm;
    r.model = row;
    const Eigen::Vector3d axis_point = truth_from_model * centreline.FrameAt(row.station_mm).origin;
    r.true_station_mm = truth.Locate(axis_point).station_mm;
    r.clean = IsCleanStation(truth, r.true_station_mm, options.clean_margin_mm);
    const auto ring =
        TrueRing(truth, centreline, truth_from_model, row.station_mm, options.ring_directions);
    if (ring) {
      r.truth = MeasureRing(*ring, profile.nominal_diameter_mm, profile_options);
      r.truth.station_mm = row.station_mm;
      r.truth.coverage = 1.0;
    } else {
      r.truth.station_mm = row.station_mm;
      r.truth.circumference_mm = r.truth.mean_diameter_mm = r.truth.ovality_en_pct =
          r.truth.ovality_astm_pct = r.truth.height_mm = r.truth.width_mm = kNaN;
    }
    // NaN propagates where the row or the truth is missing.
    r.circumference_error_pct =
        100.0 * (row.circumference_mm - r.truth.circumference_mm) / r.truth.circumference_mm;
    r.mean_diameter_error_mm = row.mean_diameter_mm - r.truth.mean_diameter_mm;
    r.ovality_en_error_pct = row.ovality_en_pct - r.truth.ovality_en_pct;
    r.ovality_astm_error_pct = row.ovality_astm_pct - r.truth.ovality_astm_pct;
    r.height_error_mm = row.height_mm - r.truth.height_mm;
    r.width_error_mm = row.width_mm - r.truth.width_mm;
    if (r.clean && std::isfinite(r.circumference_error_pct)) {
      ++e.clean_rows;
      circumference.push_back(r.circumference_error_pct);
      mean_diameter.push_back(r.mean_diameter_error_mm);
      ovality_en.push_back(r.ovality_en_error_pct);
      ovality_astm.push_back(r.ovality_astm_error_pct);
      height.push_back(r.height_error_mm);
      width.push_back(r.width_error_mm);
    }
    e.rows.push_back(r);
  }
  e.circumference_pct = Summarise(std::move(circumference));
  e.mean_diameter_mm = Summarise(std::move(mean_diameter));
  e.ovality_en_pct = Summarise(std::move(ovality_en));
  e.ovality_astm_pct = Summarise(std::move(ovality_astm));
  e.height_mm = Summarise(std::move(height));
  e.width_mm = Summarise(std::move(width));
  return e;
}

std::string ProfileEvaluationToJson(const ProfileEvaluation& e) {
  // NaN is not JSON: a missing error is null.
  const auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nullptr; };
  // Over no row there is no error to give: null, not 0.
  const auto summary = [&number](const AbsErrorSummary& s) {
    const auto value = [&](double x) { return s.rows > 0 ? number(x) : nullptr; };
    return nlohmann::json{{"rows", s.rows},
                          {"median_abs", value(s.median)},
                          {"p95_abs", value(s.p95)},
                          {"max_abs", value(s.max)}};
  };
  nlohmann::json rows = nlohmann::json::array();
  for (const ProfileRowEvaluation& r : e.rows) {
    rows.push_back({{"station_mm", r.station_mm},
                    {"true_station_mm", r.true_station_mm},
                    {"clean", r.clean},
                    {"coverage", r.model.coverage},
                    {"circumference_mm", number(r.model.circumference_mm)},
                    {"true_circumference_mm", number(r.truth.circumference_mm)},
                    {"circumference_error_pct", number(r.circumference_error_pct)},
                    {"ovality_en_pct", number(r.model.ovality_en_pct)},
                    {"true_ovality_en_pct", number(r.truth.ovality_en_pct)},
                    {"ovality_astm_pct", number(r.model.ovality_astm_pct)},
                    {"true_ovality_astm_pct", number(r.truth.ovality_astm_pct)},
                    {"height_error_mm", number(r.height_error_mm)},
                    {"width_error_mm", number(r.width_error_mm)}});
  }
  const nlohmann::json j = {{"clean_rows", e.clean_rows},
                            {"circumference_pct", summary(e.circumference_pct)},
                            {"mean_diameter_mm", summary(e.mean_diameter_mm)},
                            {"ovality_en_pct", summary(e.ovality_en_pct)},
                            {"ovality_astm_pct", summary(e.ovality_astm_pct)},
                            {"height_mm", summary(e.height_mm)},
                            {"width_mm", summary(e.width_mm)},
                            {"rows", rows}};
  return j.dump(2);
}

}  // namespace sewer3d
