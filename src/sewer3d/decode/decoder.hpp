#pragma once
/// \file
/// The single-shot decoder (paper §decode) for one module: Niblack binarisation, sub-pixel
/// spots, lattice recovery, window lookup with single-bit correction and voting. Buffers are
/// kept between frames. The result maps camera spots to array positions (mod the array
/// size), handed on as CodedObservations; triangulate/ picks the tile with the epipolar
/// constraint.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/decode/codewords.hpp"
#include "sewer3d/decode/lattice.hpp"
#include "sewer3d/decode/niblack.hpp"
#include "sewer3d/decode/spots.hpp"
#include "sewer3d/pattern/codebook.hpp"

namespace sewer3d {

struct DecoderOptions {
  NiblackOptions niblack;
  SpotOptions spots;
  LatticeOptions lattice;
  CodewordOptions codewords;
  /// Depth (mm) at which the module's lattice steps are predicted; the prediction only seeds
  /// the per-spot refinement.
  double prediction_depth_mm = 150.0;
};

struct DecodeResult {
  std::vector<Spot> spots;
  LatticeLabels lattice;
  std::vector<SpotCode> codes;
  CodewordStats stats;
  double seconds_binarise = 0, seconds_spots = 0, seconds_lattice = 0, seconds_codewords = 0;
};

/// A decoded camera spot: where it is and which array element it shows, known modulo the
/// array size (the tile along the epipolar line is chosen by triangulate/). What the decoder
/// hands on to triangulation and calibration.
struct CodedObservation {
  Eigen::Vector2d camera_px;  ///< spot centre, camera pixel (pixel centres at integers)
  int row_mod = 0;            ///< array row, 0 .. rows − 1
  int col_mod = 0;            ///< array column, 0 .. cols − 1
};

/// One observation per decoded spot, in the order of `decoded.codes`.
std::vector<CodedObservation> CodedObservations(const DecodeResult& decoded);

class Decoder {
 public:
  /// `pattern` is the module's matrix; windows wrap around it when constraints.torus.
  Decoder(const ModuleDescription& module, const BinaryArray& pattern,
          const PatternConstraints& constraints, const DecoderOptions& options);

  /// Decodes one pattern image (8- or 16-bit grey, the module's camera size).
  DecodeResult Decode(const cv::Mat& image);

  /// Lattice steps the module predicts at a camera pixel.
  LatticeSteps PredictSteps(const Eigen::Vector2d& pixel) const;

 private:
  ModuleDescription module_;
  BinaryArray pattern_;
  Codebook codebook_;
  DecoderOptions options_;
  NiblackBinariser binariser_;
  cv::Mat1b mask_;
  SpotWorkspace spot_workspace_;
  int grid_step_ = 32;
  std::vector<LatticeSteps> predicted_;  // coarse grid over the image
  int grid_cols_ = 0, grid_rows_ = 0;
};

}  // namespace sewer3d
