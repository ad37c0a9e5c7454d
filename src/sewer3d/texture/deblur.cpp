#include "sewer3d/texture/deblur.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <opencv2/core.hpp>
#include <set>
#include <vector>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Floor of the Wiener K for which the DC-normalised filter (1 + K) H / (H² + K) peaks at
// max_gain: its maximum over H is (1 + K) / (2 √K), so √K = g − √(g² − 1).
double NoiseToSignalFloor(double max_gain) {
  const double root = max_gain - std::sqrt(max_gain * max_gain - 1.0);
  return root * root;
}

// Robust noise sigma: neighbouring pixels across the travel direction share the same blur, so
// their difference is texture plus noise; its median absolute value is dominated by the noise
// on smooth walls (MAD / 0.6745, divided by √2 for the difference of two samples). `lines` has
// the travel along its rows, so the neighbours across travel are the next row.
double EstimateNoiseSigma(const cv::Mat1f& lines) {
  std::vector<float> diffs;
  diffs.reserve(static_cast<size_t>(lines.total()));
  for (int r = 0; r + 1 < lines.rows; ++r) {
    for (int c = 0; c < lines.cols; ++c) {
      const float d = lines(r + 1, c) - lines(r, c);
      if (std::isfinite(d)) diffs.push_back(std::abs(d));
    }
  }
  if (diffs.empty()) return 0.0;
  auto mid = diffs.begin() + static_cast<std::ptrdiff_t>(diffs.size() / 2);
  std::nth_element(diffs.begin(), mid, diffs.end());
  return *mid / 0.6745 / std::numbers::sqrt2;
}

// One line (3 channels as 3 rows) restored with one filter per length bin; each pixel blends
// the results of the two bins around its length. Wiener filter Ŝ = W · G with
// W(ω) = (1 + K(ω)) H / (H² + K(ω)), H(ω) = sinc(ω L / 2) the response of a centred box of
// length L, scaled to W(0) = 1 (brightness kept) and clamped to ±max_gain. The noise-to-signal
// ratio grows with frequency, K(ω) = K0 ω / π (image spectra fall with frequency, noise is
// white): low frequencies are restored fully, the highest ones least, which halves the ringing
// at sharp steps compared with a constant K of the same gain bound (measured, docs).
void RestoreLine(const cv::Mat1f& line3, const float* length_px, const DeblurOptions& o, double k,
                 cv::Mat1f& out3) {
  const int w = line3.cols;
  std::map<int, std::vector<std::pair<int, float>>> bins;  // bin -> (pixel, weight)
  float longest = 0.0F;
  for (int u = 0; u < w; ++u) {
    const float len = length_px[u];
    if (!(len >= o.min_length_px)) continue;
    const double b = std::min<double>(len, o.max_length_px) / o.bin_px;
    const int b0 = static_cast<int>(std::floor(b));
    const float frac = static_cast<float>(b - b0);
    bins[b0].emplace_back(u, 1.0F - frac);
    if (frac > 0.0F) bins[b0 + 1].emplace_back(u, frac);
    longest = std::max(longest, len);
  }
  line3.copyTo(out3);
  if (bins.empty()) return;
  for (const auto& [bin, members] : bins) {
    for (const auto& [u, weight] : members) {
      for (int c = 0; c < 3; ++c) out3(c, u) = 0.0F;
    }
  }
  // Mirrored padding: the DFT's periodic wrap would otherwise ring at the line's ends.
  const int pad = static_cast<int>(std::ceil(std::min<double>(longest, o.max_length_px))) * 2 + 8;
  const int n = cv::getOptimalDFTSize(w + 2 * pad);
  cv::Mat1f padded;
  cv::copyMakeBorder(line3, padded, 0, 0, pad, n - w - pad, cv::BORDER_REFLECT_101);
  cv::Mat spectrum, filtered, restored;
  cv::dft(padded, spectrum, cv::DFT_ROWS | cv::DFT_COMPLEX_OUTPUT);
  for (const auto& [bin, members] : bins) {
    const double length = bin * o.bin_px;
    filtered = spectrum.clone();
    for (int j = 0; j < n; ++j) {
      const double omega = 2.0 * std::numbers::pi * std::min(j, n - j) / n;
      const double x = 0.5 * omega * length;
      const double h = x < 1e-9 ? 1.0 : std::sin(x) / x;
      const double kw = k * omega / std::numbers::pi;
      const double gain = std::clamp((1.0 + kw) * h / (h * h + kw), -o.max_gain, o.max_gain);
      for (int c = 0; c < 3; ++c) filtered.at<cv::Vec2f>(c, j) *= static_cast<float>(gain);
    }
    cv::dft(filtered, restored,
            cv::DFT_ROWS | cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
    const cv::Mat1f r = restored;
    for (const auto& [u, weight] : members) {
      for (int c = 0; c < 3; ++c) out3(c, u) += weight * r(c, u + pad);
    }
  }
}

}  // namespace

void DeblurOptions::Check() const {
  ValidatePositive("bin_px", bin_px);
  ValidateNotNegative("min_length_px", min_length_px);
  SEWER3D_VALIDATE(max_length_px > min_length_px && max_length_px <= 512.0, "max_length_px",
                   "must exceed min_length_px and be <= 512, got " << max_length_px);
  SEWER3D_VALIDATE(max_gain >= 1.0, "max_gain", "must be >= 1, got " << max_gain);
  SEWER3D_VALIDATE(std::isfinite(noise_sigma), "noise_sigma", "must be finite");
}

cv::Mat2f BlurDisplacementPx(const CameraModel& camera, const cv::Mat1f& depth_mm,
                             const Eigen::Vector3d& velocity_mm_s, double exposure_ms) {
  const Eigen::Vector3d half = 0.5e-3 * exposure_ms * velocity_mm_s;
  cv::Mat2f out(depth_mm.size(), cv::Vec2f(kNaN, kNaN));
  cv::parallel_for_(cv::Range(0, depth_mm.rows), [&](const cv::Range& rows) {
    for (int v = rows.start; v < rows.end; ++v) {
      for (int u = 0; u < depth_mm.cols; ++u) {
        const float z = depth_mm(v, u);
        if (!(z > 0.0F)) continue;
        const auto xy = camera.Unproject({double(u), double(v)});
        if (!xy) continue;
        const Eigen::Vector3d p = Eigen::Vector3d(xy->x(), xy->y(), 1.0) * z;
        const auto start = camera.Project(p + half), end = camera.Project(p - half);
        if (!start || !end) continue;
        const Eigen::Vector2d d = *end - *start;
        out(v, u) = cv::Vec2f(static_cast<float>(d.x()), static_cast<float>(d.y()));
      }
    }
  });
  return out;
}

DeblurResult Deblur(const cv::Mat3f& image, const cv::Mat1f& depth_mm, const CameraModel& camera,
                    const Eigen::Vector3d& velocity_mm_s, double exposure_ms,
                    const DeblurOptions& options) {
  options.Check();
  ValidateNotNegative("exposure_ms", exposure_ms);
  SEWER3D_VALIDATE(velocity_mm_s.allFinite(), "velocity_mm_s", "must be finite");
  SEWER3D_VALIDATE(image.size() == depth_mm.size(), "depth_mm", "must have the image's size");
  const auto t0 = std::chrono::steady_clock::now();
  DeblurResult result;
  DeblurReport& report = result.report;
  const cv::Mat2f disp = BlurDisplacementPx(camera, depth_mm, velocity_mm_s, exposure_ms);
  // The dominant travel axis: the mean displacement (the travel has one sign over the image).
  cv::Scalar mean_d(0, 0);
  int valid = 0;
  for (const cv::Vec2f& d : disp) {
    if (!std::isfinite(d[0])) continue;
    mean_d += cv::Scalar(d[0], d[1]);
    ++valid;
  }
  report.along_columns = std::abs(mean_d[1]) >= std::abs(mean_d[0]);
  const int axis = report.along_columns ? 1 : 0;
  report.off_axis_deg = valid == 0
                            ? 0.0
                            : std::atan2(std::abs(mean_d[1 - axis]), std::abs(mean_d[axis])) *
                                  180.0 / std::numbers::pi;
  result.blur_length_px.create(image.size());
  report.min_length_px = std::numeric_limits<double>::infinity();
  for (int v = 0; v < image.rows; ++v) {
    for (int u = 0; u < image.cols; ++u) {
      const float len = std::abs(disp(v, u)[axis]);
      result.blur_length_px(v, u) = len;
      if (!std::isfinite(len)) continue;
      report.min_length_px = std::min<double>(report.min_length_px, len);
      report.max_length_px = std::max<double>(report.max_length_px, len);
      if (len >= options.min_length_px) ++report.pixels_restored;
      if (len > options.max_length_px) ++report.pixels_clamped;
    }
  }
  if (valid == 0) report.min_length_px = 0.0;
  // Lines along the travel are rows of `lines` (transposed when travel runs along columns).
  cv::Mat3f lines;
  cv::Mat1f lengths;
  if (report.along_columns) {
    cv::transpose(image, lines);
    cv::transpose(result.blur_length_px, lengths);
  } else {
    lines = image.clone();
    lengths = result.blur_length_px;
  }
  // K0 = (noise / signal)² per channel, averaged; never below the floor that bounds the gain.
  std::vector<cv::Mat1f> channels;
  cv::split(lines, channels);
  double noise = 0.0, signal = 0.0;
  for (const cv::Mat1f& channel : channels) {
    noise += EstimateNoiseSigma(channel) / 3.0;
    cv::Scalar mean, std_dev;
    cv::meanStdDev(channel, mean, std_dev);
    signal += std_dev[0] / 3.0;
  }
  report.noise_sigma = options.noise_sigma > 0.0 ? options.noise_sigma : noise;
  report.noise_to_signal = std::max(NoiseToSignalFloor(options.max_gain),
                                    std::pow(report.noise_sigma / std::max(signal, 1e-12), 2.0));
  std::set<int> all_bins;
  for (const float len : lengths) {
    if (len >= options.min_length_px) {
      all_bins.insert(
          static_cast<int>(std::min<double>(len, options.max_length_px) / options.bin_px));
    }
  }
  report.bins = static_cast<int>(all_bins.size());
  cv::Mat3f restored(lines.size());
  cv::parallel_for_(cv::Range(0, lines.rows), [&](const cv::Range& range) {
    cv::Mat1f line3(3, lines.cols), out3;
    for (int r = range.start; r < range.end; ++r) {
      for (int u = 0; u < lines.cols; ++u) {
        for (int c = 0; c < 3; ++c) line3(c, u) = lines(r, u)[c];
      }
      RestoreLine(line3, lengths[r], options, report.noise_to_signal, out3);
      for (int u = 0; u < lines.cols; ++u) {
        for (int c = 0; c < 3; ++c) restored(r, u)[c] = out3(c, u);
      }
    }
  });
  if (report.along_columns) {
    cv::transpose(restored, result.image);
  } else {
    result.image = restored;
  }
  report.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace sewer3d
