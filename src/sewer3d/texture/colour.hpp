#pragma once
/// \file
/// Colour science for the texture images (docs/texture.md, "Shading and colour correction"):
/// the sRGB transfer function (IEC 61966-2-1), linear sRGB (D65) ↔ CIE XYZ ↔ CIE L*a*b*
/// (D65 white), the CIEDE2000 colour difference (Sharma, Wu, Dalal 2005) and the acceptance
/// metric of the correction: mean ΔE00 against a reference after one global per-channel gain.
///
/// Conventions: a pixel as an Eigen::Vector3d is in RGB order; an image is an OpenCV matrix in
/// OpenCV's BGR channel order. "Linear" values are linear sRGB with 1 = the encoding's white
/// (they may exceed 1 after correction). A Lab image (cv::Mat3f) holds (L*, a*, b*) in that
/// channel order. XYZ is scaled so that the white (R = G = B = 1) has Y = 1.

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace sewer3d {

/// sRGB decoding of one value in [0, 1] (IEC 61966-2-1; values outside are mirrored in sign
/// and extended along the same curve).
double SrgbToLinear(double encoded);
/// sRGB encoding of one linear value (inverse of SrgbToLinear).
double LinearToSrgb(double linear);

/// CIE XYZ (Y of white = 1) of a linear sRGB colour (RGB order), D65 primaries.
Eigen::Vector3d LinearRgbToXyz(const Eigen::Vector3d& rgb);
Eigen::Vector3d XyzToLinearRgb(const Eigen::Vector3d& xyz);
/// The white point: XYZ of R = G = B = 1, ≈ D65 (0.95047, 1, 1.08883).
Eigen::Vector3d WhiteXyz();
/// CIE L*a*b* (CIE 15) relative to WhiteXyz(); and back.
Eigen::Vector3d XyzToLab(const Eigen::Vector3d& xyz);
Eigen::Vector3d LabToXyz(const Eigen::Vector3d& lab);
Eigen::Vector3d LinearRgbToLab(const Eigen::Vector3d& rgb);
Eigen::Vector3d LabToLinearRgb(const Eigen::Vector3d& lab);

/// CIEDE2000 colour difference ΔE00 of two L*a*b* colours (kL = kC = kH = 1), following the
/// implementation notes of Sharma, Wu and Dalal, Color Res. Appl. 30(1), 2005 (eqs. 1-23).
double DeltaE2000(const Eigen::Vector3d& lab1, const Eigen::Vector3d& lab2);

/// 8-bit sRGB-encoded BGR (as cv::imread gives it) → linear BGR in [0, 1] (lookup table).
cv::Mat3f LinearFromSrgb8(const cv::Mat3b& srgb_bgr);
/// Linear BGR → 8-bit sRGB-encoded BGR, clipped to [0, 1] and rounded.
cv::Mat3b Srgb8FromLinear(const cv::Mat3f& linear_bgr);
/// Linear BGR → (L*, a*, b*) image; NaN pixels stay NaN.
cv::Mat3f LabFromLinear(const cv::Mat3f& linear_bgr);
/// (L*, a*, b*) image → linear BGR (not clipped).
cv::Mat3f LinearFromLab(const cv::Mat3f& lab);

/// ΔE00 statistics of two images over a mask.
struct DeltaEStats {
  int pixels = 0;       ///< pixels compared (mask set and both colours finite)
  double mean = 0.0;    ///< mean ΔE00 (0 when no pixel)
  double median = 0.0;  ///< median ΔE00
  double p95 = 0.0;     ///< 95th percentile of ΔE00
};

/// ΔE00 between two linear BGR images of the same size, over the pixels where `mask` is
/// non-zero (an empty mask means all pixels) and both images are finite. Throws
/// std::invalid_argument on a size mismatch.
DeltaEStats CompareDeltaE2000(const cv::Mat3f& linear_bgr_a, const cv::Mat3f& linear_bgr_b,
                              const cv::Mat1b& mask = cv::Mat1b());

/// How FitChannelGains chooses the gain of each channel.
enum class GainFit {
  kLeastSquares,  ///< g = Σ image·reference / Σ image² (linear values)
  kMedianRatio,   ///< g = median of reference / image (robust to outliers and clipping)
};

/// The one global gain per channel (exposure and white balance), BGR order, that brings
/// `linear_bgr` closest to `reference_linear_bgr` over `mask` (empty = all finite pixels;
/// pixels where either image is ≤ 0 or non-finite are skipped for kMedianRatio). Throws
/// std::invalid_argument on a size mismatch; returns (1, 1, 1) where a channel has no data.
cv::Vec3d FitChannelGains(const cv::Mat3f& linear_bgr, const cv::Mat3f& reference_linear_bgr,
                          const cv::Mat1b& mask = cv::Mat1b(), GainFit fit = GainFit::kMedianRatio);

/// `linear_bgr` with channel c multiplied by gains_bgr[c].
cv::Mat3f ApplyChannelGains(const cv::Mat3f& linear_bgr, const cv::Vec3d& gains_bgr);

/// The acceptance metric of the shading and colour correction: the gains of FitChannelGains,
/// then ΔE00 between the gained image and the reference.
struct GainedDeltaE {
  cv::Vec3d gains_bgr{1.0, 1.0, 1.0};
  DeltaEStats delta_e;
};
GainedDeltaE CompareAfterGlobalGain(const cv::Mat3f& linear_bgr,
                                    const cv::Mat3f& reference_linear_bgr,
                                    const cv::Mat1b& mask = cv::Mat1b(),
                                    GainFit fit = GainFit::kMedianRatio);

}  // namespace sewer3d
