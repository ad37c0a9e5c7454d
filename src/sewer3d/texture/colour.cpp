#include "sewer3d/texture/colour.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

constexpr double kPi = std::numbers::pi;

// Linear sRGB → XYZ for the sRGB primaries and D65 white (derived from the chromaticities of
// IEC 61966-2-1 with the white at Y = 1); its row sums are the white point, so R = G = B
// maps to a* = b* = 0 exactly.
const Eigen::Matrix3d& RgbToXyzMatrix() {
  static const Eigen::Matrix3d m = (Eigen::Matrix3d() << 0.4124564, 0.3575761, 0.1804375,  //
                                    0.2126729, 0.7151522, 0.0721750,                       //
                                    0.0193339, 0.1191920, 0.9503041)
                                       .finished();
  return m;
}

const Eigen::Matrix3d& XyzToRgbMatrix() {
  static const Eigen::Matrix3d m = RgbToXyzMatrix().inverse();
  return m;
}

// CIE 15 companding of L*a*b*: cube root above (6/29)³, a line below.
constexpr double kDelta = 6.0 / 29.0;
double LabF(double t) {
  return t > kDelta * kDelta * kDelta ? std::cbrt(t) : t / (3.0 * kDelta * kDelta) + 4.0 / 29.0;
}
double LabFInverse(double f) {
  return f > kDelta ? f * f * f : 3.0 * kDelta * kDelta * (f - 4.0 / 29.0);
}

double Deg(double rad) { return rad * 180.0 / kPi; }
double Rad(double deg) { return deg * kPi / 180.0; }

void CheckSameSize(const cv::Mat& a, const cv::Mat& b, const char* field) {
  SEWER3D_VALIDATE(a.size() == b.size(), field,
                   "size " << b.cols << "x" << b.rows << " differs from the image's " << a.cols
                           << "x" << a.rows);
}

bool Selected(const cv::Mat1b& mask, int r, int c) { return mask.empty() || mask(r, c) != 0; }

bool Finite(const cv::Vec3f& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

Eigen::Vector3d Rgb(const cv::Vec3f& bgr) { return {bgr[2], bgr[1], bgr[0]}; }

}  // namespace

double SrgbToLinear(double encoded) {
  const double v = std::abs(encoded);
  const double linear = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  return std::copysign(linear, encoded);
}

double LinearToSrgb(double linear) {
  const double v = std::abs(linear);
  const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
  return std::copysign(encoded, linear);
}

Eigen::Vector3d LinearRgbToXyz(const Eigen::Vector3d& rgb) { return RgbToXyzMatrix() * rgb; }
Eigen::Vector3d XyzToLinearRgb(const Eigen::Vector3d& xyz) { return XyzToRgbMatrix() * xyz; }
Eigen::Vector3d WhiteXyz() { return RgbToXyzMatrix() * Eigen::Vector3d::Ones(); }

Eigen::Vector3d XyzToLab(const Eigen::Vector3d& xyz) {
  const Eigen::Vector3d n = xyz.cwiseQuotient(WhiteXyz());
  const double fx = LabF(n.x()), fy = LabF(n.y()), fz = LabF(n.z());
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Eigen::Vector3d LabToXyz(const Eigen::Vector3d& lab) {
  const double fy = (lab.x() + 16.0) / 116.0;
  const double fx = fy + lab.y() / 500.0;
  const double fz = fy - lab.z() / 200.0;
  return Eigen::Vector3d(LabFInverse(fx), LabFInverse(fy), LabFInverse(fz))
      .cwiseProduct(WhiteXyz());
}

Eigen::Vector3d LinearRgbToLab(const Eigen::Vector3d& rgb) { return XyzToLab(LinearRgbToXyz(rgb)); }
Eigen::Vector3d LabToLinearRgb(const Eigen::Vector3d& lab) { return XyzToLinearRgb(LabToXyz(lab)); }

double DeltaE2000(const Eigen::Vector3d& lab1, const Eigen::Vector3d& lab2) {
  const double pow25_7 = std::pow(25.0, 7.0);
  // Eqs. 2-7: a* rescaled by G so that near-neutral colours get the right hue; C', h' (deg).
  const double c_mean = 0.5 * (std::hypot(lab1.y(), lab1.z()) + std::hypot(lab2.y(), lab2.z()));
  const double c7 = std::pow(c_mean, 7.0);
  const double g = 0.5 * (1.0 - std::sqrt(c7 / (c7 + pow25_7)));
  const double a1 = (1.0 + g) * lab1.y(), a2 = (1.0 + g) * lab2.y();
  const double c1 = std::hypot(a1, lab1.z()), c2 = std::hypot(a2, lab2.z());
  const auto hue = [](double b, double a) {
    if (a == 0.0 && b == 0.0) return 0.0;
    const double h = Deg(std::atan2(b, a));
    return h < 0.0 ? h + 360.0 : h;
  };
  const double h1 = hue(lab1.z(), a1), h2 = hue(lab2.z(), a2);
  // Eqs. 8-11: differences; the hue difference takes the short way round.
  const bool achromatic = c1 * c2 == 0.0;
  double dh = h2 - h1;
  if (achromatic) {
    dh = 0.0;
  } else if (dh > 180.0) {
    dh -= 360.0;
  } else if (dh < -180.0) {
    dh += 360.0;
  }
  const double d_l = lab2.x() - lab1.x();
  const double d_c = c2 - c1;
  const double d_h = 2.0 * std::sqrt(c1 * c2) * std::sin(Rad(dh) / 2.0);
  // Eqs. 12-22: means (the mean hue also the short way round), weights and rotation term.
  const double l_bar = 0.5 * (lab1.x() + lab2.x());
  const double c_bar = 0.5 * (c1 + c2);
  double h_bar = h1 + h2;
  if (!achromatic) {
    if (std::abs(h1 - h2) <= 180.0) {
      h_bar = 0.5 * (h1 + h2);
    } else {
      h_bar = h1 + h2 < 360.0 ? 0.5 * (h1 + h2 + 360.0) : 0.5 * (h1 + h2 - 360.0);
    }
  }
  const double t = 1.0 - 0.17 * std::cos(Rad(h_bar - 30.0)) + 0.24 * std::cos(Rad(2.0 * h_bar)) +
                   0.32 * std::cos(Rad(3.0 * h_bar + 6.0)) -
                   0.20 * std::cos(Rad(4.0 * h_bar - 63.0));
  const double d_theta = 30.0 * std::exp(-std::pow((h_bar - 275.0) / 25.0, 2.0));
  const double c_bar7 = std::pow(c_bar, 7.0);
  const double r_c = 2.0 * std::sqrt(c_bar7 / (c_bar7 + pow25_7));
  const double l50 = (l_bar - 50.0) * (l_bar - 50.0);
  const double s_l = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double s_c = 1.0 + 0.045 * c_bar;
  const double s_h = 1.0 + 0.015 * c_bar * t;
  const double r_t = -std::sin(Rad(2.0 * d_theta)) * r_c;
  // Eq. 23.
  const double tl = d_l / s_l, tc = d_c / s_c, th = d_h / s_h;
  return std::sqrt(tl * tl + tc * tc + th * th + r_t * tc * th);
}

cv::Mat3f LinearFromSrgb8(const cv::Mat3b& srgb_bgr) {
  std::array<float, 256> lut{};
  for (int i = 0; i < 256; ++i) lut[i] = static_cast<float>(SrgbToLinear(i / 255.0));
  cv::Mat3f out(srgb_bgr.size());
  for (int r = 0; r < srgb_bgr.rows; ++r) {
    for (int c = 0; c < srgb_bgr.cols; ++c) {
      const cv::Vec3b& v = srgb_bgr(r, c);
      out(r, c) = cv::Vec3f(lut[v[0]], lut[v[1]], lut[v[2]]);
    }
  }
  return out;
}

cv::Mat3b Srgb8FromLinear(const cv::Mat3f& linear_bgr) {
  // Code i is chosen for linear values in [t[i-1], t[i]) with t[i] the linear value of the
  // encoded (i + 0.5) / 255: the same rounding as lround(255 LinearToSrgb(v)), without a pow.
  std::array<float, 255> t{};
  for (int i = 0; i < 255; ++i) t[i] = static_cast<float>(SrgbToLinear((i + 0.5) / 255.0));
  cv::Mat3b out(linear_bgr.size());
  for (int r = 0; r < linear_bgr.rows; ++r) {
    for (int c = 0; c < linear_bgr.cols; ++c) {
      for (int k = 0; k < 3; ++k) {
        const float v = linear_bgr(r, c)[k];
        out(r, c)[k] = std::isfinite(v)
                           ? static_cast<uchar>(std::upper_bound(t.begin(), t.end(), v) - t.begin())
                           : 0;
      }
    }
  }
  return out;
}

cv::Mat3f LabFromLinear(const cv::Mat3f& linear_bgr) {
  cv::Mat3f out(linear_bgr.size());
  for (int r = 0; r < linear_bgr.rows; ++r) {
    for (int c = 0; c < linear_bgr.cols; ++c) {
      const Eigen::Vector3d lab = LinearRgbToLab(Rgb(linear_bgr(r, c)));
      out(r, c) = cv::Vec3f(static_cast<float>(lab.x()), static_cast<float>(lab.y()),
                            static_cast<float>(lab.z()));
    }
  }
  return out;
}

cv::Mat3f LinearFromLab(const cv::Mat3f& lab) {
  cv::Mat3f out(lab.size());
  for (int r = 0; r < lab.rows; ++r) {
    for (int c = 0; c < lab.cols; ++c) {
      const cv::Vec3f& v = lab(r, c);
      const Eigen::Vector3d rgb = LabToLinearRgb({v[0], v[1], v[2]});
      out(r, c) = cv::Vec3f(static_cast<float>(rgb.z()), static_cast<float>(rgb.y()),
                            static_cast<float>(rgb.x()));
    }
  }
  return out;
}

DeltaEStats CompareDeltaE2000(const cv::Mat3f& linear_bgr_a, const cv::Mat3f& linear_bgr_b,
                              const cv::Mat1b& mask) {
  CheckSameSize(linear_bgr_a, linear_bgr_b, "second image");
  if (!mask.empty()) CheckSameSize(linear_bgr_a, mask, "mask");
  std::vector<double> d;
  for (int r = 0; r < linear_bgr_a.rows; ++r) {
    for (int c = 0; c < linear_bgr_a.cols; ++c) {
      const cv::Vec3f& a = linear_bgr_a(r, c);
      const cv::Vec3f& b = linear_bgr_b(r, c);
      if (!Selected(mask, r, c) || !Finite(a) || !Finite(b)) continue;
      d.push_back(DeltaE2000(LinearRgbToLab(Rgb(a)), LinearRgbToLab(Rgb(b))));
    }
  }
  DeltaEStats stats;
  stats.pixels = static_cast<int>(d.size());
  if (d.empty()) return stats;
  double sum = 0.0;
  for (double v : d) sum += v;
  stats.mean = sum / static_cast<double>(d.size());
  std::sort(d.begin(), d.end());
  stats.median = d[d.size() / 2];
  stats.p95 = d[std::min(d.size() - 1, static_cast<size_t>(0.95 * static_cast<double>(d.size())))];
  return stats;
}

cv::Vec3d FitChannelGains(const cv::Mat3f& linear_bgr, const cv::Mat3f& reference_linear_bgr,
                          const cv::Mat1b& mask, GainFit fit) {
  CheckSameSize(linear_bgr, reference_linear_bgr, "reference image");
  if (!mask.empty()) CheckSameSize(linear_bgr, mask, "mask");
  cv::Vec3d gains(1.0, 1.0, 1.0);
  for (int k = 0; k < 3; ++k) {
    double sum_xy = 0.0, sum_xx = 0.0;
    std::vector<double> ratios;
    for (int r = 0; r < linear_bgr.rows; ++r) {
      for (int c = 0; c < linear_bgr.cols; ++c) {
        const double x = linear_bgr(r, c)[k], y = reference_linear_bgr(r, c)[k];
        if (!Selected(mask, r, c) || !std::isfinite(x) || !std::isfinite(y)) continue;
        sum_xy += x * y;
        sum_xx += x * x;
        if (x > 0.0 && y > 0.0) ratios.push_back(y / x);
      }
    }
    if (fit == GainFit::kLeastSquares && sum_xx > 0.0) gains[k] = sum_xy / sum_xx;
    if (fit == GainFit::kMedianRatio && !ratios.empty()) {
      auto mid = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
      std::nth_element(ratios.begin(), mid, ratios.end());
      gains[k] = *mid;
    }
  }
  return gains;
}

cv::Mat3f ApplyChannelGains(const cv::Mat3f& linear_bgr, const cv::Vec3d& gains_bgr) {
  cv::Mat3f out;
  cv::multiply(linear_bgr, cv::Scalar(gains_bgr[0], gains_bgr[1], gains_bgr[2]), out);
  return out;
}

GainedDeltaE CompareAfterGlobalGain(const cv::Mat3f& linear_bgr,
                                    const cv::Mat3f& reference_linear_bgr, const cv::Mat1b& mask,
                                    GainFit fit) {
  GainedDeltaE out;
  out.gains_bgr = FitChannelGains(linear_bgr, reference_linear_bgr, mask, fit);
  out.delta_e =
      CompareDeltaE2000(ApplyChannelGains(linear_bgr, out.gains_bgr), reference_linear_bgr, mask);
  return out;
}

}  // namespace sewer3d
