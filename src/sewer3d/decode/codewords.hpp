#pragma once
/// \file
/// Reading the 6 x 6 bit windows of the recovered lattice and looking them up (paper
/// §decode): a node is 1 when a spot sits on it, 0 when it is observed empty. Every window
/// that decodes (one wrong bit corrected) votes, for each spot it contains, for the offset
/// between lattice and array coordinates; each spot takes the offset most windows agree on.

#include <opencv2/core.hpp>
#include <vector>

#include "sewer3d/decode/lattice.hpp"
#include "sewer3d/pattern/codebook.hpp"

namespace sewer3d {

/// A spot with its array position (row mod array rows, col mod array cols).
struct SpotCode {
  int spot = 0;
  int row = 0;
  int col = 0;
  int votes = 0;    ///< windows agreeing
  int dissent = 0;  ///< windows voting for another position
};

struct CodewordStats {
  int windows_read = 0;     ///< windows with all 36 nodes inside the image
  int windows_decoded = 0;  ///< found in the codebook (exactly or with one bit corrected)
  int bits_corrected = 0;
  int spots_decoded = 0;
  int spots_ambiguous = 0;  ///< votes too few or split
};

struct CodewordOptions {
  /// Windows that must agree on a spot's position. Two overlapping windows share 30 of their
  /// 36 nodes: where labels are garbled (the lattice at a wall feature's edge) two of them
  /// matched a wrong element (the demo's full-size wall: a point 2.8 mm deep); three cost
  /// 0.1–0.4 % of the accuracy captures' points.
  int min_votes = 3;
  double min_agreement = 0.6;  ///< share of the spot's votes the winner must hold
  int border_px = 3;           ///< nodes closer than this to the image border are unobservable
};

std::vector<SpotCode> DecodeCodewords(const std::vector<Spot>& spots, const LatticeLabels& lattice,
                                      const Codebook& codebook, int array_rows, int array_cols,
                                      cv::Size image_size, const CodewordOptions& options,
                                      CodewordStats* stats);

}  // namespace sewer3d
