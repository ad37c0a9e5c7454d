#include "sewer3d/simeval/inspection_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "sewer3d/core/units.hpp"
#include "sewer3d/inspect/defects.hpp"
#include "sewer3d/model/unroll.hpp"

namespace sewer3d {
namespace {

struct TrueItem {
  std::string id, code;
  double station_mm = 0.0;  ///< world station (start for continuous items)
  double clock_h = 12.0;
  double length_mm = 0.0;
  std::vector<TrueItemMatch::Value> values;
};

double DiameterAt(const PipeGeometry& g, double station_mm) {
  const PipeWorld& w = g.world();
  for (std::size_t i = w.sections.size(); i-- > 0;) {
    if (station_mm >= g.SectionStartMm(static_cast<int>(i))) return w.sections[i].diameter_mm;
  }
  return w.sections.front().diameter_mm;
}

struct SpallTruth {
  double area_mm2 = 0.0;
  double depth_mean_mm = 0.0;
};

/// The true spalled patch measured as the inspection measures one (defects.hpp): its cells at
/// least half as deep as its median (the area), and their mean depth at least the inspection's
/// `spall_rim_mm` inside that outline, on a 0.25 mm grid of the simulator's own rough patch.
SpallTruth MeasureSpall(const PipeFeature& f, std::uint64_t seed, double radius_mm) {
  constexpr double kStep = 0.25;
  const int rows = static_cast<int>(std::floor((f.length_mm + 2.0) / kStep)) + 1;
  const int cols = static_cast<int>(std::floor((f.width_mm + 2.0) / kStep)) + 1;
  cv::Mat1f depth(rows, cols);  // into the wall; ≤ 0 outside the patch
  std::vector<double> inside;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      const double ds = -0.5 * f.length_mm - 1.0 + i * kStep;
      const double arc = -0.5 * f.width_mm - 1.0 + j * kStep;
      depth(i, j) = static_cast<float>(
          -PipeFeatureDisplacementMm(f, ds, arc / radius_mm, radius_mm, seed, nullptr));
      if (depth(i, j) > 0.0F) inside.push_back(depth(i, j));
    }
  }
  std::nth_element(inside.begin(), inside.begin() + static_cast<std::ptrdiff_t>(inside.size() / 2),
                   inside.end());
  const double half = 0.5 * inside[inside.size() / 2];
  std::vector<cv::Point> core;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      if (depth(i, j) > 0.0F && depth(i, j) >= half) core.emplace_back(j, i);
    }
  }
  const int rim = static_cast<int>(std::lround(DefectOptions{}.spall_rim_mm / kStep));
  std::vector<cv::Point> inner = InteriorCells(core, rim, rim);
  if (inner.empty()) inner = core;
  double sum = 0.0;
  for (const cv::Point& p : inner) sum += depth(p);
  return {static_cast<double>(core.size()) * kStep * kStep,
          sum / static_cast<double>(inner.size())};
}

std::vector<TrueItem> TrueItems(const PipeGeometry& g) {
  const PipeWorld& w = g.world();
  std::vector<TrueItem> items;
  for (std::size_t i = 0; i < w.joints.size(); ++i) {
    const PipeJoint& j = w.joints[i];
    // A joint only deflected is placed where its next pipe turns toward (as BAJ C is).
    items.push_back(
        {j.id,
         "BAJ",
         g.SectionStartMm(static_cast<int>(i) + 1),
         j.offset_mm > 0.0 || j.deflection_deg <= 0.0 ? j.offset_clock_h : j.deflection_clock_h,
         0.0,
         {{"offset_mm", j.offset_mm, 0.0},
          {"gap_mm", j.gap_mm, 0.0},
          {"deflection_deg", j.deflection_deg, 0.0}}});
  }
  for (std::size_t i = 0; i < w.sections.size(); ++i) {
    const PipeSection& s = w.sections[i];
    if (s.ovality_pct <= 0.0) continue;
    items.push_back({"D" + std::to_string(i + 1),
                     "BAA",
                     g.SectionStartMm(static_cast<int>(i)),
                     s.ovality_clock_h,
                     s.length_mm,
                     {{"deformation_pct", s.ovality_pct, 0.0}}});
  }
  for (std::size_t k = 0; k < w.features.size(); ++k) {
    const PipeFeature& f = w.features[k];
    const double dn = DiameterAt(g, f.station_mm);
    TrueItem t{f.id, "", f.station_mm, f.clock_h, 0.0, {}};
    switch (f.type) {
      case PipeFeature::Type::kConnection:
        t.code = f.intrusion_mm > 0.0 ? "BAG" : "BCA";
        t.values = {{"bore_diameter_mm", f.diameter_mm, 0.0}};
        if (f.intrusion_mm > 0.0) {
          t.values.push_back({"intrusion_mm", f.intrusion_mm, 0.0});
          t.values.push_back({"intrusion_pct_of_dn", 100.0 * f.intrusion_mm / dn, 0.0});
        }
        break;
      case PipeFeature::Type::kSpalling: {
        const SpallTruth truth = MeasureSpall(f, w.material_seed + k, 0.5 * dn);
        t.code = "BAF";
        t.values = {{"area_mm2", truth.area_mm2, 0.0}, {"depth_mean_mm", truth.depth_mean_mm, 0.0}};
        break;
      }
      case PipeFeature::Type::kCrack:
        t.code = "BAB";
        t.values = {{"length_mm", f.length_mm, 0.0}, {"angle_deg", f.angle_deg, 0.0}};
        break;
      case PipeFeature::Type::kDeposit: {
        const double r = 0.5 * dn, theta = 2.0 * std::acos((r - f.height_mm) / r);
        t.code = "BBC";
        t.length_mm = f.length_mm;
        t.values = {{"height_mm", f.height_mm, 0.0},
                    {"cross_section_loss_pct",
                     100.0 * (theta - std::sin(theta)) / (2.0 * std::numbers::pi), 0.0}};
        break;
      }
      case PipeFeature::Type::kWet:  // no shape to measure: infiltration shows in the texture
      default:
        continue;
    }
    items.push_back(t);
  }
  return items;
}

/// The true item's place in the model's (station, clock): its wall point moved into the model
/// frame and unrolled about the model's centreline.
CylPoint InModel(const PipeGeometry& g, const TrueItem& t, const Rigid3d& model_from_truth,
                 const Centreline& centreline) {
  int section = 0;
  while (section + 1 < static_cast<int>(g.world().sections.size()) &&
         t.station_mm >= g.SectionStartMm(section + 1))
    ++section;
  const Rigid3d frame = g.SectionFrame(section, t.station_mm - g.SectionStartMm(section));
  const double r = 0.5 * g.world().sections[section].diameter_mm;
  const Eigen::Vector3d p = frame * (r * ClockDirection(ClockHoursToRad(t.clock_h)));
  return Unroll(centreline, model_from_truth * p, centreline.station0_mm);
}

double ClockDiffH(double a, double b, double period) { return std::remainder(a - b, period); }

bool Compatible(const std::string& truth_code, const std::string& code) {
  return truth_code == code || (truth_code == "BAG" && code == "BCA");
}

}  // namespace

InspectionEvaluation EvaluateObservations(const std::vector<Observation>& observations,
                                          const PipeGeometry& truth,
                                          const Rigid3d& truth_from_model,
                                          const Centreline& centreline,
                                          const InspectionEvaluationOptions& o) {
  InspectionEvaluation e;
  std::vector<bool> used(observations.size(), false);
  const Rigid3d model_from_truth = truth_from_model.Inverse();
  for (const TrueItem& t : TrueItems(truth)) {
    CylPoint at = InModel(truth, t, model_from_truth, centreline);
    if (o.truth_from_model_near)
      at = InModel(truth, t, o.truth_from_model_near(at.station_mm).Inverse(), centreline);
    TrueItemMatch m;
    m.truth_id = t.id;
    m.code = t.code;
    m.station_mm = at.station_mm;
    m.clock_h = at.clock_rad * 6.0 / std::numbers::pi;
    m.inspected =
        at.station_mm + t.length_mm >= o.inspected_from_mm && at.station_mm <= o.inspected_to_mm;
    m.values = t.values;
    // Deformation is symmetric: its clock is known modulo 6 h.
    const double period = t.code == "BAA" ? 6.0 : 12.0;
    int best = -1;
    for (std::size_t i = 0; i < observations.size(); ++i) {
      const Observation& ob = observations[i];
      if (used[i] || !Compatible(t.code, ob.code)) continue;
      const double ds = std::abs(ob.station_mm - m.station_mm);
      if (ds > o.match_station_mm ||
          std::abs(ClockDiffH(ob.clock_h, m.clock_h, period)) > o.match_clock_h)
        continue;
      if (best < 0 || ds < std::abs(observations[best].station_mm - m.station_mm))
        best = static_cast<int>(i);
    }
    if (m.inspected) ++e.inspected;
    if (best >= 0) {
      const Observation& ob = observations[best];
      used[best] = true;
      // "found of inspected": an item outside the inspected stations is matched, not counted.
      if (m.inspected) ++e.found;
      m.observation_id = ob.id;
      m.station_error_mm = ob.station_mm - m.station_mm;
      m.clock_error_h = ClockDiffH(ob.clock_h, m.clock_h, period);
      for (TrueItemMatch::Value& v : m.values) {
        const Quantity* q = ob.Find(v.name);
        v.measured = q ? q->value : std::numeric_limits<double>::quiet_NaN();
      }
    }
    e.items.push_back(m);
  }
  for (std::size_t i = 0; i < observations.size(); ++i) {
    const double s = observations[i].station_mm;
    if (!used[i] && s >= o.inspected_from_mm && s <= o.inspected_to_mm)
      e.invented.push_back(observations[i].id);
  }
  return e;
}

}  // namespace sewer3d
