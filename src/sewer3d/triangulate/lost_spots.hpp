#pragma once
/// \file
/// Spots the binariser missed, looked for where the frame's own points say they must be: a
/// lit element without a point whose mesh neighbours have points lies, on a smooth surface, at
/// the camera pixel an affine map of their element coordinates predicts. A dark patch (a
/// deposit, a board's black square) or a black wall at a grey wall's exposure leaves spots a
/// grey level or two above the background: too faint for the binariser's floor, found by
/// FaintSpotAt where they are expected. The lattice bridges the patch from its edges inward,
/// round by round, each spot found adding a neighbour for the next.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "sewer3d/core/neighbours.hpp"
#include "sewer3d/decode/decoder.hpp"
#include "sewer3d/decode/faint_spot.hpp"
#include "sewer3d/triangulate/correspondences.hpp"
#include "sewer3d/triangulate/element_mesh.hpp"

namespace sewer3d {

struct LostSpotOptions {
  /// false: a frame's points are the spots the decoder read.
  bool enabled = true;
  /// Points needed among the element's mesh neighbours and their neighbours to predict its
  /// pixel (the affine map has three unknowns per coordinate; more check them).
  int min_neighbours = 5;
  /// The map's largest residual at those neighbours: beyond it they do not lie on one smooth
  /// surface (a depth step between them: no spot is predicted across it). This fraction of
  /// the frame's epipolar tolerance (its spots' scatter), at least max_fit_px: at 2592 px the
  /// `paper` profile scatters spots twice as far in pixels as at 1296, and a fixed 1 px
  /// stopped the growth into a black wall at 60 % of its spots (87 % with this).
  double max_fit_tolerance = 0.7;
  double max_fit_px = 1.0;
  /// A step nearby: a point of the next ring out (the neighbours' neighbours' neighbours) off
  /// the map by more than this many times that limit, and nothing is predicted. Without it
  /// the map of neighbours that all lie on one wall carries the wall past its edge over a
  /// joint's gap, and faint light there became a point 8 mm off (2592 px).
  double step_fits = 3.0;
  /// The spot's centre within the frame's epipolar tolerance of the prediction, and within
  /// this fraction of the nearest neighbour's distance; the search disk is 0.3 of that
  /// distance and the background ring reaches 0.5 of it, short of the next spot.
  double max_offset = 0.2;
  /// Rounds of growth into a patch (each from the spots the last one found).
  int max_rounds = 30;
  FaintSpotOptions spot;
  void Check() const;
};

/// Finds lost spots for one module's frames; what depends on the module only (the mesh's
/// neighbour lists) is built once.
class LostSpotFinder {
 public:
  /// `mesh`: the module's lit elements (MeshLitElements); its grid and neighbours are copied.
  LostSpotFinder(const ElementMesh& mesh, int array_rows, int array_cols,
                 const LostSpotOptions& options);

  /// Looks for the spot of every lit element without a point among `points` (their elements
  /// and `observations`' pixels) next to elements with points. A spot the binariser found
  /// (`spots`) near the prediction is left alone: the decoder or the outlier tests had their
  /// reasons. Each spot found that triangulates with its element within `tolerance_px` is
  /// appended to `observations` and `points`. Returns the number added.
  int Find(const cv::Mat& image, const std::vector<Spot>& spots, const Triangulator& triangulator,
           double tolerance_px, std::vector<CodedObservation>& observations,
           std::vector<TriangulatedPoint>& points);

 private:
  struct Found {
    int cell;
    CodedObservation observation;
    TriangulatedPoint point;
  };
  /// The spot of grid cell `cell`'s element, if one is found.
  std::optional<Found> Look(int cell, const cv::Mat& image, double level_scale,
                            const Triangulator& triangulator, double tolerance_px,
                            const std::vector<CodedObservation>& observations,
                            const std::vector<TriangulatedPoint>& points) const;
  bool NearDetectedSpot(const Eigen::Vector2d& px, double radius) const;
  /// Whether a point of the cells one ring beyond ring_ lies farther than `limit_px` from
  /// where `map` puts it.
  bool StepNearby(const Eigen::Matrix<double, 3, 2>& map, double limit_px,
                  const std::vector<CodedObservation>& observations,
                  const std::vector<TriangulatedPoint>& points) const;

  ElementMesh grid_;  ///< the mesh's element grid (no triangles: its neighbours are below)
  NeighbourLists neighbours_;
  int array_rows_, array_cols_;
  LostSpotOptions options_;
  std::vector<int> point_of_;              ///< per grid cell: index into the points, −1 none
  mutable std::vector<int> ring_, outer_;  ///< Look's buffers
  // The binariser's spots bucketed by kSpotCell px squares (CSR), rebuilt per frame.
  std::vector<int> spot_start_;
  std::vector<Eigen::Vector2d> spot_px_;
  int spot_grid_cols_ = 0, spot_grid_rows_ = 0;
};

}  // namespace sewer3d
