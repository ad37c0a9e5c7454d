#pragma once
/// \file
/// Reading one acquisition's images from a capture run for the processing stages: the file of
/// each image of a triplet, checked against its module's camera size, textures demosaiced when
/// the run's camera has a colour filter array (run.json `color_filter`). Errors are FileError
/// naming the image.

#include <filesystem>
#include <opencv2/core.hpp>

#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

/// The run's image file of `kind` for acquisition `a`; where acquisitions.csv has no such row,
/// the file the run's layout would have (so a failure can name it).
std::filesystem::path AcquisitionImageFile(const CaptureRun& run, const Acquisition& a,
                                           ImageKind kind);

/// Checks that the rig describes the images: for each module, its first and last readable
/// images (missing or undecodable ones are passed over: their acquisitions fail on their own)
/// must have the size of its camera. Throws FileError naming rig.json and the module's camera
/// when every one checked differs, since then the rig, not an image, is wrong. Likewise run.json
/// when its color_filter does not match the first texture image that decodes (a raw mosaic
/// has one channel).
void CheckRigMatchesImages(const CaptureRun& run);

/// The pattern image, grey 8- or 16-bit as stored, the module's camera size.
cv::Mat ReadPatternImage(const CaptureRun& run, const Acquisition& a);

/// A texture image (texture_before or texture_after) as 8-bit BGR at the module's camera size:
/// colour PNGs as stored, raw mosaics (run.json `color_filter` "RGGB") demosaiced.
cv::Mat3b ReadTextureImage(const CaptureRun& run, const Acquisition& a, ImageKind kind);

/// The same as linear float BGR in [0, 1]: a run's texture values are linear sensor values
/// (docs/formats.md), so only scaled.
cv::Mat3f ReadLinearTexture(const CaptureRun& run, const Acquisition& a, ImageKind kind);

}  // namespace sewer3d
