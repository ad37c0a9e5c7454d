#pragma once
/// \file
/// The data of a capture run (docs/formats.md) as the processing chain sees it: the rig, every
/// image with its time, the odometry readings, and what run.json says. io/ reads and writes it
/// (LoadRun); the simulator fills the same types. Nothing here reads files or knows the truth.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sewer3d/pattern/binary_array.hpp"
#include "sewer3d/run/inclinometer.hpp"
#include "sewer3d/run/odometry.hpp"
#include "sewer3d/run/rig.hpp"

namespace sewer3d {

/// The three images of an acquisition, in the order they are taken: texture (ring light on,
/// projector off), pattern (projector on), texture.
enum class ImageKind { kTextureBefore = 0, kPattern = 1, kTextureAfter = 2 };
inline constexpr std::array<ImageKind, 3> kImageKinds = {
    ImageKind::kTextureBefore, ImageKind::kPattern, ImageKind::kTextureAfter};

/// "texture_before", "pattern", "texture_after" (acquisitions.csv's `image` column).
const char* ImageKindName(ImageKind kind);
/// The kind named `name`; nullopt when it names none.
std::optional<ImageKind> ParseImageKind(std::string_view name);

/// One image of the run: a row of acquisitions.csv.
struct RunImage {
  int module = 0;   ///< index into the rig's modules
  int counter = 0;  ///< the module's acquisition number
  ImageKind kind = ImageKind::kPattern;
  double time_s = 0.0;  ///< middle of the exposure, seconds from the start of the run
  double exposure_ms = 0.0;
  std::string file;  ///< relative to the run folder
  /// Listed in acquisitions.csv but no file there when the run was loaded (LoadRun): its
  /// acquisition fails when its images are read, the others are processed.
  bool missing = false;
};

/// Where a run keeps an image: "m<module>/<counter, 6 digits>_<kind>" (docs/formats.md), under
/// images/ with ".png" and, in simulated runs, under truth/depth/ with ".tiff".
std::string ImageStem(int module, int counter, ImageKind kind);

/// run.json: what the folder is and where it came from.
struct RunInfo {
  bool complete = true;  ///< false: the capture stopped part-way (images may be missing)
  std::string created_by;
  std::string scenario;  ///< simulated runs: the scenario's name
  std::uint64_t seed = 0;
  double acquisition_period_s = 0.0;
  /// The texture images' colour filter: "none" (3-channel colour images) or "RGGB" (one-channel
  /// Bayer raw, row 0 R G R G …; OpenCV demosaics it with cv::COLOR_BayerBG2BGR).
  std::string color_filter = "none";
};

/// A whole capture run in memory (images stay on disk: `folder / image.file`).
struct CaptureRun {
  std::filesystem::path folder;
  RunInfo info;
  Rig rig;
  std::vector<BinaryArray> patterns;  ///< each module's pattern matrix, as rig.modules
  std::vector<RunImage> images;       ///< sorted by time
  /// Sorted by time; as LoadRun gives it, the readings CheckOdometry kept.
  std::vector<OdometryReading> odometry;
  /// What LoadRun's CheckOdometry dropped (reversals) and the gaps left: where `odometry` is
  /// only a guess (OdometryUncertaintyAt). Empty for a run not read by LoadRun.
  OdometryFindings odometry_findings;
  /// The carrier's inclinometer (inclinometer.csv), sorted by time; empty: the run has none.
  std::vector<InclinometerReading> inclinometer;
};

/// One module's acquisition `counter`: its triplet as indices into the run's images (−1 where
/// an image is missing).
struct Acquisition {
  int module = 0;
  int counter = 0;
  std::array<int, 3> image{-1, -1, -1};  ///< indexed by ImageKind

  int Image(ImageKind kind) const { return image[static_cast<int>(kind)]; }
};

/// Groups images into acquisitions, ordered by (module, counter). Throws std::invalid_argument
/// when two images share module, counter and kind.
std::vector<Acquisition> GroupAcquisitions(const std::vector<RunImage>& images);

}  // namespace sewer3d
