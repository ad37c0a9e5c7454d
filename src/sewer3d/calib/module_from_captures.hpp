#pragma once
/// \file
/// Module calibration from checkerboard captures (docs/calibration.md, `sewer3d calibrate
/// module`): per pose, the board's corners in the texture image and the pattern image decoded
/// and triangulated with the nominal module, which only predicts the lattice and picks each
/// spot's pattern tile; the corners carried into the projector by local homographies (Moreno &
/// Taubin 2012); then CalibrateModule, the corners carried again with the first pass's lens
/// models, and CalibrateModule once more.

#include <opencv2/core.hpp>
#include <vector>

#include "sewer3d/calib/module_calibration.hpp"
#include "sewer3d/camera/module.hpp"
#include "sewer3d/decode/decoder.hpp"
#include "sewer3d/pattern/binary_array.hpp"
#include "sewer3d/pattern/constraints.hpp"
#include "sewer3d/triangulate/correspondences.hpp"

namespace sewer3d {

/// The printed board: cols x rows inner corners at square_mm pitch (BoardCorners).
struct BoardLayout {
  int cols = 9, rows = 6;
  double square_mm = 10.0;
  void Check() const;
};

/// Options of the decoding and corner transfer; the defaults are `sewer3d calibrate module`'s.
struct ModuleCalibratorOptions {
  DecoderOptions decoder;  ///< decoding the pattern images
  /// Picking each spot's pattern tile with the nominal module, whose geometry is rough (a
  /// projector millimetres off its design place, so spots lie pixels off their nominal
  /// epipolar lines). max_reprojection_px is capped at a quarter of the distance between
  /// tiles (the default pattern: 6 rows of 8 px), so the tile stays unambiguous.
  TriangulationOptions triangulation = [] {
    TriangulationOptions o;
    o.max_reprojection_px = 12.0;
    return o;
  }();
  /// Both passes' corner transfer; its lens models must be unset (the second pass sets them).
  CornerTransferOptions corner_transfer;
  /// A pose is used when at least this fraction of its corners is carried into the projector
  /// (the others count for the camera only): a far or steep pose loses the corners of a few
  /// squares whose spots do not decode, and is still worth its camera corners and the rest.
  double min_carried_fraction = 0.5;
  void Check() const;
};

/// What became of one capture.
struct CaptureOutcome {
  enum class Status {
    kUsed,
    kBoardNotFound,      ///< the whole board was not found in the texture image
    kCornersNotCarried,  ///< too many corners have too few decoded spots around them
    kRepeated,           ///< the board lies where it did in a capture already used
  };
  Status status = Status::kUsed;
  int repeats = -1;         ///< kRepeated: the capture used before (0-based, in order of use)
  int corners = 0;          ///< board corners (0 when the board was not found)
  int corners_missing = 0;  ///< corners not carried into the projector (kUsed: used without)
  int spots_decoded = 0;    ///< spots with a projector element (0 when the board was not found)
};

/// Both passes of a module calibration and the module they give.
struct ModuleFromCapturesResult {
  ModuleCalibrationResult first_pass;   ///< corners carried by homographies in pixels
  ModuleCalibrationResult second_pass;  ///< carried again with first_pass's lens models
  int views_retransferred = 0;          ///< views whose corners the second pass replaced
  /// The nominal module (pattern, layout, extra fields) with the second pass's camera,
  /// projector and projector_from_camera.
  ModuleDescription module;
};

/// Collects captures one pose at a time (keeps corners and decoded spots, not images), then
/// calibrates. Views are numbered in the order their captures were used.
class ModuleCalibrator {
 public:
  /// `nominal`: the design module, close enough to predict the spot lattice and pick the
  /// pattern tile; `pattern` its matrix and `constraints` those it satisfies. Throws
  /// std::invalid_argument on invalid options, module or board.
  ModuleCalibrator(const ModuleDescription& nominal, const BinaryArray& pattern,
                   const PatternConstraints& constraints, const BoardLayout& board,
                   const ModuleCalibratorOptions& options = {});

  /// One pose: `texture_grey` with the board lit (projector off), `pattern_image` (8- or
  /// 16-bit grey, projector on), both the nominal camera's size (else std::invalid_argument).
  /// The pose is used when every corner is found, enough of them are carried into the
  /// projector (min_carried_fraction), and the board does not lie where it did in a pose
  /// already used (the same capture twice adds nothing but weight).
  CaptureOutcome AddCapture(const cv::Mat1b& texture_grey, const cv::Mat& pattern_image);

  /// Captures kept so far (the views of Calibrate, in the order they were added).
  int captures_used() const { return static_cast<int>(views_.size()); }

  /// The two-pass calibration of the captures used so far. Needs three of them with every
  /// corner carried (std::invalid_argument otherwise).
  ModuleFromCapturesResult Calibrate() const;

 private:
  ModuleDescription nominal_;
  BoardLayout board_;
  ModuleCalibratorOptions options_;
  Decoder decoder_;
  Triangulator triangulator_;
  std::vector<ModuleCalibrationView> views_;
  std::vector<SpotCorrespondences> spots_;
};

}  // namespace sewer3d
