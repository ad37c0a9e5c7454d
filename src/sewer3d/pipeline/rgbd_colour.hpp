#pragma once
/// \file
/// The RGB-D stage's colour (paper §3.2; docs/rgbd.md, docs/texture.md), after the geometry
/// pass:
/// - reference pass, per module: the reference light (texture/shading.hpp) estimated from up to
///   `reference_frames` of its acquisitions (texture_before with the pattern's depth map),
///   kept in `WS/rgbd/reference/m<k>.json` with a picture `m<k>.png`;
/// - seam pass: the modules' relative colour gains from the wall neighbouring modules see at
///   the same counter (texture/module_gains.hpp), kept in `WS/rgbd/reference/module_gains.json`;
/// - colour pass, per acquisition: both texture images deblurred along the travel (speed from
///   odometry, the depth map, the pipe prior where it has none), mapped to the pattern instant
///   (AKAZE motion across the triplet), shading- and colour-corrected in L*a*b*; the colour
///   image, the cloud recoloured from it, and the acquisition report.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sewer3d/pipeline/rgbd_geometry.hpp"
#include "sewer3d/run/capture_run.hpp"
#include "sewer3d/texture/deblur.hpp"
#include "sewer3d/texture/module_gains.hpp"
#include "sewer3d/texture/shading.hpp"
#include "sewer3d/texture/triplet_mapping.hpp"

namespace sewer3d {

struct RgbdColourOptions {
  int reference_frames = 40;  ///< acquisitions per module the reference light is estimated from
  ReferenceLightOptions reference;
  bool deblur = true;
  DeblurOptions deblurring;
  TripletMappingOptions mapping;
  CorrectionOptions correction;
  /// Counters at which neighbouring modules' seams are compared (evenly spread over the run).
  int seam_counters = 12;
  SeamOptions seams;
  /// The pipe prior's diameter where a frame has too few points to measure its own (the wall's
  /// median distance from the carrier axis).
  double nominal_diameter_mm = 300.0;
  /// Also write WS/rgbd/debug/m<k>/<counter>_captured.png (texture_before as captured, sRGB
  /// for display), _mapped.png (deblurred and mapped, before shading correction) and
  /// _deblur_crop.png (a crop before | after deblurring, enlarged 3x).
  bool debug_images = false;
  void Check() const;
};

/// Where the colour of the RGB-D outputs comes from, in words, as workspace.json and the
/// reports record it; by default "texture triplet: deblurred, mapped to the pattern instant,
/// shading and colour corrected" ("not deblurred" with --no-deblur, "(in Lab)" for Lab);
/// `deblur_note`, when given, in brackets after "deblurred" (how many were not, and why).
std::string RgbdColorSource(const RgbdColourOptions& options, const std::string& deblur_note = "");

/// The colour options as recorded in workspace.json (a JSON object).
std::string RgbdColourOptionsJson(const RgbdColourOptions& options);

/// Results of the reference pass for one module.
struct RgbdReferenceResult {
  int module = 0;
  std::optional<ReferenceLight> reference;  ///< nullopt: no acquisition could be used
  bool skipped = false;                     ///< read back from an earlier run
  ReferenceLightReport report;
  std::string file, reason;  ///< failure: the file at fault and why
};

/// The reference light of `module` from its acquisitions in `acquisitions` whose geometry is
/// done (evenly spread, at most options.reference_frames), or the one an earlier run wrote.
/// Unreadable images are passed over (the colour pass reports them).
RgbdReferenceResult RgbdReferencePass(const CaptureRun& run, int module,
                                      const std::vector<Acquisition>& acquisitions,
                                      const std::filesystem::path& rgbd_folder,
                                      const RgbdColourOptions& options);

/// The modules' colour gains measured at up to options.seam_counters counters (each module's
/// texture_before corrected by its own reference, compared with its neighbour's over the wall
/// both measured), or those an earlier run wrote. `correctors[m]` null: module m takes no part.
ModuleGains RgbdSeamPass(const CaptureRun& run, const std::vector<Acquisition>& acquisitions,
                         const std::filesystem::path& rgbd_folder,
                         const std::vector<const ShadingCorrector*>& correctors,
                         const RgbdColourOptions& options);

/// The colour pass of acquisition `a` into `rgbd_folder` (`WS/rgbd`): skipped when its report
/// exists; failed (in the result, never thrown) when its geometry is missing, an image is bad or
/// its module has no reference light (`corrector` null). `corrector`: the module's, built from
/// its reference light (shared by the workers; Correct is const); `module_gain`: its
/// ModuleGains entry, divided out after the correction.
RgbdAcquisitionResult RgbdColourPass(const CaptureRun& run, const Acquisition& a,
                                     const std::filesystem::path& rgbd_folder,
                                     const ShadingCorrector* corrector,
                                     const cv::Vec3d& module_gain,
                                     const RgbdColourOptions& options);

}  // namespace sewer3d
