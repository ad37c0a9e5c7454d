#include "sewer3d/simeval/rgbd_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <tuple>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/registration_io.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/pipeline/acquisition_images.hpp"
#include "sewer3d/sim/pipe_world.hpp"
#include "sewer3d/simio/render_json.hpp"
#include "sewer3d/simio/scenario_io.hpp"
#include "sewer3d/simio/truth_io.hpp"
#include "sewer3d/texture/colour.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

// What the evaluation knows that the stage does not.
class Truth {
 public:
  explicit Truth(const CaptureRun& run)
      : run_(run), pipe_(ReadScenario(run.folder / "truth" / "scenario.json").world) {
    for (const TruthPose& p : ReadTruthPoses(run.folder / "truth" / "poses.csv", run.images.size()))
      poses_[{p.module, p.counter, static_cast<int>(p.kind)}] = p.world_from_carrier;
  }

  Rigid3d WorldFromCamera(int module, int counter, ImageKind kind) const {
    const auto it = poses_.find({module, counter, static_cast<int>(kind)});
    if (it == poses_.end())
      throw FileError(run_.folder / "truth" / "poses.csv",
                      "no pose of " + ImageStem(module, counter, kind));
    return it->second * run_.rig.modules.at(module).carrier_from_camera;
  }

  // Linear albedo (BGR) each pixel of an image saw; NaN where no wall.
  cv::Mat3f Albedo(int module, int counter, ImageKind kind) const {
    const fs::path file =
        run_.folder / "truth" / "albedo" / (ImageStem(module, counter, kind) + "_linear.png");
    const cv::Mat raw = ReadImage(file, cv::IMREAD_UNCHANGED);
    if (raw.type() != CV_16UC3) throw FileError(file, "not a 16-bit colour albedo image");
    cv::Mat3f albedo;
    raw.convertTo(albedo, CV_32F, 1.0 / 65535.0);
    for (auto& p : albedo) {
      if (p[0] + p[1] + p[2] <= 0.0f) p = cv::Vec3f(NAN, NAN, NAN);
    }
    return albedo;
  }

  const PipeGeometry& pipe() const { return pipe_; }

 private:
  const CaptureRun& run_;
  PipeGeometry pipe_;
  std::map<std::tuple<int, int, int>, Rigid3d> poses_;
};

struct ColourSample {
  cv::Vec3f value, truth;  // linear BGR
  int material = 0;
  int module = 0;
};

struct Images {
  cv::Mat3f captured;  // texture_before as captured, linear
  cv::Mat3f colour;    // the stage's colour image, linear
  cv::Mat1f depth;
};

Images ReadImages(const CaptureRun& run, const fs::path& rgbd, const Acquisition& a) {
  Images im;
  im.captured = ReadLinearTexture(run, a, ImageKind::kTextureBefore);
  // Colour and depth checked as registration reads them (types, one size).
  const RgbdPairInput stage = ReadRgbdForRegistration(rgbd, a.module, a.counter);
  im.colour = LinearFromSrgb8(stage.color_bgr);
  im.depth = stage.depth_mm;
  return im;
}

cv::Rect CropAround(const cv::Mat1f& depth, int side) {
  double su = 0, sv = 0;
  long long n = 0;
  for (int v = 0; v < depth.rows; v += 4) {
    for (int u = 0; u < depth.cols; u += 4) {
      if (std::isfinite(depth(v, u))) su += u, sv += v, ++n;
    }
  }
  const int cu = n > 0 ? static_cast<int>(su / n) : depth.cols / 2;
  const int cv_ = n > 0 ? static_cast<int>(sv / n) : depth.rows / 2;
  side = std::min({side, depth.cols, depth.rows});
  const int x = std::clamp(cu - side / 2, 0, depth.cols - side);
  const int y = std::clamp(cv_ - side / 2, 0, depth.rows - side);
  return {x, y, side, side};
}

cv::Mat1f Grey(const cv::Mat3f& bgr, const cv::Rect& crop) {
  cv::Mat1f grey;
  cv::cvtColor(bgr(crop), grey, cv::COLOR_BGR2GRAY);
  cv::patchNaNs(grey, 0.0);
  return grey;
}

// Shift (px) of `image` against the true albedo `truth` over a crop, by phase correlation; NaN
// where it cannot mean anything: a true wall of under 2 % contrast in the window (plastic pipe:
// 0.2–0.4 %, concrete ~30 %; on plastic it read shifts of 10–200 px that were noise) or a
// peak under 0.07 (concrete 1.0–1.1).
double Misregistration(const cv::Mat3f& image, const cv::Mat3f& truth, const cv::Rect& crop) {
  constexpr double kMinContrast = 0.02, kMinResponse = 0.07;
  const cv::Mat1f true_grey = Grey(truth, crop);
  cv::Scalar mean, sd;
  cv::meanStdDev(true_grey, mean, sd);
  if (!(sd[0] >= kMinContrast * mean[0])) return NAN;
  cv::Mat window;
  cv::createHanningWindow(window, crop.size(), CV_32F);
  double response = 0.0;
  const cv::Point2d shift = cv::phaseCorrelate(Grey(image, crop), true_grey, window, &response);
  return response >= kMinResponse ? std::hypot(shift.x, shift.y) : NAN;
}

double Median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

cv::Vec3d MedianRatioGains(const std::vector<ColourSample>& samples) {
  cv::Vec3d gains;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> ratios;
    for (const ColourSample& s : samples) {
      if (s.value[c] > 1e-3f && s.truth[c] > 0.0f) ratios.push_back(s.truth[c] / s.value[c]);
    }
    gains[c] = ratios.empty() ? 1.0 : Median(ratios);
  }
  return gains;
}

Eigen::Vector3d Lab(const cv::Vec3f& bgr, const cv::Vec3d& gains) {
  return LinearRgbToLab(Eigen::Vector3d(bgr[2] * gains[2], bgr[1] * gains[1], bgr[0] * gains[0]));
}

double DeltaE(const cv::Vec3f& a, const cv::Vec3d& ga, const cv::Vec3f& b, const cv::Vec3d& gb) {
  return DeltaE2000(Lab(a, ga), Lab(b, gb));
}

// A finished acquisition whose files changed since is an error, not one to pass over.
bool FinishedIntact(const fs::path& rgbd, const Acquisition& a) {
  const RgbdFiles files = RgbdAcquisitionFiles(rgbd, a.module, a.counter);
  if (const std::string damaged = RgbdDamagedFile(files); !damaged.empty()) {
    throw FileError(damaged,
                    "not the size the rgbd stage wrote (cut short or replaced since); run "
                    "`sewer3d rgbd` to redo the acquisition");
  }
  return RgbdAcquisitionDone(files);
}

std::vector<Acquisition> Chosen(const CaptureRun& run, const fs::path& rgbd, int per_module) {
  std::map<int, std::vector<Acquisition>> complete;
  for (const Acquisition& a : GroupAcquisitions(run.images)) {
    if (FinishedIntact(rgbd, a)) complete[a.module].push_back(a);
  }
  std::vector<Acquisition> chosen;
  for (const auto& [module, list] : complete) {
    const int n = std::min<int>(per_module, static_cast<int>(list.size()));
    for (int k = 0; k < n; ++k) chosen.push_back(list[(2 * k + 1) * list.size() / (2 * n)]);
  }
  return chosen;
}

}  // namespace

void RgbdEvaluationOptions::Check() const {
  SEWER3D_VALIDATE(acquisitions_per_module >= 1, "acquisitions_per_module", "must be ≥ 1");
  SEWER3D_VALIDATE(stride_px >= 1, "stride_px", "must be ≥ 1");
  SEWER3D_VALIDATE(crop_px >= 32, "crop_px", "must be ≥ 32");
  SEWER3D_VALIDATE(colour_smoothing_px >= 1, "colour_smoothing_px", "must be ≥ 1");
  SEWER3D_VALIDATE(seam_smoothing_px >= 1, "seam_smoothing_px", "must be ≥ 1");
}

namespace {

// Box mean of side `side` (1: the image itself).
cv::Mat3f Smoothed(const cv::Mat3f& image, int side) {
  if (side <= 1) return image;
  cv::Mat3f out;
  cv::blur(image, out, cv::Size(side, side));
  return out;
}

// The material each sampled pixel sees (through the true pose), or −1.
int MaterialAt(const Truth& truth, const Rigid3d& world_from_camera, const CameraModel& camera,
               int u, int v) {
  const auto xy = camera.Unproject({double(u), double(v)});
  if (!xy) return -1;
  const auto hit =
      truth.pipe().Intersect(world_from_camera.translation,
                             world_from_camera.rotation * Eigen::Vector3d(xy->x(), xy->y(), 1.0));
  return hit ? static_cast<int>(hit->material) : -1;
}

struct AcquisitionFigures {
  std::vector<ColourSample> before, after;
  std::map<int, std::vector<double>> naive_px, mapped_px;  // by the crop's main material
  std::map<int, cv::Mat3b> montage_rows;
};

cv::Mat3b MontageRow(const Images& im, const cv::Mat3f& truth, const cv::Rect& crop) {
  cv::Mat3b row;
  cv::Mat3f truth_shown = truth(crop).clone();
  cv::patchNaNs(truth_shown.reshape(1), 0.0);
  cv::hconcat(
      std::vector<cv::Mat>{Srgb8FromLinear(im.captured(crop).clone()),
                           Srgb8FromLinear(im.colour(crop).clone()), Srgb8FromLinear(truth_shown)},
      row);
  return row;
}

void Sample(const CaptureRun& run, const Truth& truth, const fs::path& rgbd, const Acquisition& a,
            const RgbdEvaluationOptions& o, AcquisitionFigures& out) {
  Images im = ReadImages(run, rgbd, a);
  const cv::Mat3f truth_before =
      Smoothed(truth.Albedo(a.module, a.counter, ImageKind::kTextureBefore), o.colour_smoothing_px);
  const cv::Mat3f truth_pattern = truth.Albedo(a.module, a.counter, ImageKind::kPattern);
  const cv::Mat3f truth_pattern_smooth = Smoothed(truth_pattern, o.colour_smoothing_px);
  const cv::Mat3f captured = Smoothed(im.captured, o.colour_smoothing_px);
  const cv::Mat3f colour = Smoothed(im.colour, o.colour_smoothing_px);
  const CameraModel camera(run.rig.modules.at(a.module).module.camera);
  const Rigid3d world_from_camera = truth.WorldFromCamera(a.module, a.counter, ImageKind::kPattern);
  std::map<int, int> votes;
  for (int v = 0; v < im.depth.rows; v += o.stride_px) {
    for (int u = 0; u < im.depth.cols; u += o.stride_px) {
      if (!std::isfinite(im.depth(v, u))) continue;
      const int material = MaterialAt(truth, world_from_camera, camera, u, v);
      if (material < 0) continue;
      ++votes[material];
      if (std::isfinite(truth_pattern_smooth(v, u)[0]))
        out.after.push_back({colour(v, u), truth_pattern_smooth(v, u), material, a.module});
      if (std::isfinite(truth_before(v, u)[0]))
        out.before.push_back({captured(v, u), truth_before(v, u), material, a.module});
    }
  }
  if (votes.empty()) return;
  const int material = std::max_element(votes.begin(), votes.end(), [](auto& x, auto& y) {
                         return x.second < y.second;
                       })->first;
  const cv::Rect crop = CropAround(im.depth, o.crop_px);
  if (const double px = Misregistration(im.captured, truth_pattern, crop); std::isfinite(px))
    out.naive_px[material].push_back(px);
  if (const double px = Misregistration(im.colour, truth_pattern, crop); std::isfinite(px))
    out.mapped_px[material].push_back(px);
  if (!out.montage_rows.count(material))
    out.montage_rows[material] = MontageRow(im, truth_pattern, crop);
}

// Colour of `image` where the world point lands in the camera at `world_from_camera`.
std::optional<cv::Vec3f> ColourAt(const cv::Mat3f& image, const CameraModel& camera,
                                  const Rigid3d& world_from_camera,
                                  const Eigen::Vector3d& p_world) {
  const auto px = camera.Project(world_from_camera.Inverse() * p_world);
  if (!px) return std::nullopt;
  const int u = static_cast<int>(std::lround(px->x())), v = static_cast<int>(std::lround(px->y()));
  if (u < 0 || v < 0 || u >= image.cols || v >= image.rows) return std::nullopt;
  const cv::Vec3f c = image(v, u);
  if (!std::isfinite(c[0] + c[1] + c[2])) return std::nullopt;
  return c;
}

// Same wall point in modules k and k + 1 of one counter: ΔE00 before and after.
void SeamPair(const CaptureRun& run, const Truth& truth, const fs::path& rgbd, const Acquisition& a,
              const Acquisition& b, const RgbdEvaluationOptions& o, const RgbdEvaluation& e,
              SeamFigures& seams, double& sum_before, double& sum_after) {
  const Images ia = ReadImages(run, rgbd, a), ib = ReadImages(run, rgbd, b);
  const cv::Mat3f ca = Smoothed(ia.colour, o.seam_smoothing_px);
  const cv::Mat3f cb = Smoothed(ib.colour, o.seam_smoothing_px);
  const cv::Mat3f ra = Smoothed(ia.captured, o.seam_smoothing_px);
  const cv::Mat3f rb = Smoothed(ib.captured, o.seam_smoothing_px);
  const CameraModel cam_a(run.rig.modules.at(a.module).module.camera);
  const CameraModel cam_b(run.rig.modules.at(b.module).module.camera);
  const Rigid3d wa = truth.WorldFromCamera(a.module, a.counter, ImageKind::kPattern);
  const Rigid3d wb = truth.WorldFromCamera(b.module, b.counter, ImageKind::kPattern);
  const Rigid3d wa0 = truth.WorldFromCamera(a.module, a.counter, ImageKind::kTextureBefore);
  const Rigid3d wb0 = truth.WorldFromCamera(b.module, b.counter, ImageKind::kTextureBefore);
  long long points = 0;
  for (int v = 0; v < ia.depth.rows; v += o.stride_px) {
    for (int u = 0; u < ia.depth.cols; u += o.stride_px) {
      const float z = ia.depth(v, u);
      if (!std::isfinite(z)) continue;
      const auto xy = cam_a.Unproject({double(u), double(v)});
      if (!xy) continue;
      const Eigen::Vector3d p_world = wa * (double(z) * Eigen::Vector3d(xy->x(), xy->y(), 1.0));
      // Seen by b: in b's depth map at the predicted depth (not hidden, not off its mesh).
      const Eigen::Vector3d p_b = wb.Inverse() * p_world;
      const auto px = cam_b.Project(p_b);
      if (!px) continue;
      const int ub = static_cast<int>(std::lround(px->x()));
      const int vb = static_cast<int>(std::lround(px->y()));
      if (ub < 0 || vb < 0 || ub >= ib.depth.cols || vb >= ib.depth.rows) continue;
      if (!(std::abs(ib.depth(vb, ub) - p_b.z()) < 1.5)) continue;
      const auto after_a = ColourAt(ca, cam_a, wa, p_world);
      const auto after_b = ColourAt(cb, cam_b, wb, p_world);
      const auto before_a = ColourAt(ra, cam_a, wa0, p_world);
      const auto before_b = ColourAt(rb, cam_b, wb0, p_world);
      if (!after_a || !after_b || !before_a || !before_b) continue;
      sum_after += DeltaE(*after_a, e.gains_after_bgr, *after_b, e.gains_after_bgr);
      sum_before += DeltaE(*before_a, e.gains_before_bgr, *before_b, e.gains_before_bgr);
      ++points;
    }
  }
  if (points > 0) ++seams.pairs;
  seams.points += points;
}

}  // namespace

RgbdEvaluation EvaluateRgbd(const CaptureRun& run, const fs::path& workspace,
                            const RgbdEvaluationOptions& o) {
  o.Check();
  const Truth truth(run);
  const fs::path rgbd = workspace / "rgbd";
  const std::vector<Acquisition> chosen = Chosen(run, rgbd, o.acquisitions_per_module);
  AcquisitionFigures figures;
  for (const Acquisition& a : chosen) Sample(run, truth, rgbd, a, o, figures);
  RgbdEvaluation e;
  e.acquisitions = static_cast<int>(chosen.size());
  e.gains_before_bgr = MedianRatioGains(figures.before);
  e.gains_after_bgr = MedianRatioGains(figures.after);
  std::map<int, std::pair<double, long long>> before, after;
  for (const ColourSample& s : figures.before) {
    before[s.material].first += DeltaE(s.value, e.gains_before_bgr, s.truth, {1, 1, 1});
    ++before[s.material].second;
  }
  for (const ColourSample& s : figures.after) {
    after[s.material].first += DeltaE(s.value, e.gains_after_bgr, s.truth, {1, 1, 1});
    ++after[s.material].second;
  }
  // Diagnostic: one gain per module instead of one for the run separates the shading's shape
  // from the modules' consistency.
  std::map<int, std::vector<ColourSample>> by_module;
  for (const ColourSample& s : figures.after) by_module[s.module].push_back(s);
  std::map<int, std::pair<double, long long>> after_module_gain;
  for (const auto& [module, samples] : by_module) {
    const cv::Vec3d gains = MedianRatioGains(samples);
    for (const ColourSample& s : samples) {
      after_module_gain[s.material].first += DeltaE(s.value, gains, s.truth, {1, 1, 1});
      ++after_module_gain[s.material].second;
    }
  }
  std::vector<cv::Mat> rows;
  for (const auto& [material, sum] : after) {
    MaterialColourFigures& m = e.materials[MaterialName(static_cast<Material>(material))];
    m.pixels = sum.second;
    m.delta_e_after = sum.first / static_cast<double>(sum.second);
    m.delta_e_after_module_gains =
        after_module_gain[material].first / static_cast<double>(after_module_gain[material].second);
    if (before.count(material))
      m.delta_e_before = before[material].first / static_cast<double>(before[material].second);
    m.acquisitions = static_cast<int>(figures.mapped_px[material].size());
    m.misregistration_naive_px = Median(figures.naive_px[material]);
    m.misregistration_mapped_px = Median(figures.mapped_px[material]);
    if (figures.montage_rows.count(material)) rows.push_back(figures.montage_rows[material]);
  }
  if (!rows.empty()) cv::vconcat(rows, e.montage);

  const int modules = static_cast<int>(run.rig.modules.size());
  double sum_before = 0, sum_after = 0;
  for (const Acquisition& a : chosen) {
    if (modules < 2) break;
    const int next = (a.module + 1) % modules;
    for (const Acquisition& b : GroupAcquisitions(run.images)) {
      if (b.module != next || b.counter != a.counter) continue;
      if (!FinishedIntact(rgbd, b)) continue;
      SeamPair(run, truth, rgbd, a, b, o, e, e.seams, sum_before, sum_after);
    }
  }
  if (e.seams.points > 0) {
    e.seams.delta_e_before = sum_before / static_cast<double>(e.seams.points);
    e.seams.delta_e_after = sum_after / static_cast<double>(e.seams.points);
  }
  return e;
}

std::string RgbdEvaluationToJson(const RgbdEvaluation& e) {
  nlohmann::json materials = nlohmann::json::object();
  for (const auto& [name, m] : e.materials) {
    materials[name] = {
        {"pixels", m.pixels},
        {"acquisitions", m.acquisitions},
        {"delta_e00_before", m.delta_e_before},
        {"delta_e00_after", m.delta_e_after},
        {"misregistration_px",
         {{"naive", m.misregistration_naive_px}, {"mapped", m.misregistration_mapped_px}}}};
  }
  const nlohmann::json j = {
      {"acquisitions", e.acquisitions},
      {"materials", materials},
      {"seams",
       {{"pairs", e.seams.pairs},
        {"points", e.seams.points},
        {"delta_e00_before", e.seams.delta_e_before},
        {"delta_e00_after", e.seams.delta_e_after}}},
      {"global_gains_bgr",
       {{"before", {e.gains_before_bgr[0], e.gains_before_bgr[1], e.gains_before_bgr[2]}},
        {"after", {e.gains_after_bgr[0], e.gains_after_bgr[1], e.gains_after_bgr[2]}}}}};
  return j.dump(2) + "\n";
}

}  // namespace sewer3d
