#pragma once
/// \file
/// From decoded spots to 3D points: the epipolar constraint of the module picks the pattern
/// tile (paper §decode) and rejects wrong decodes; DLT triangulates (paper §triangulate).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/decode/decoder.hpp"

namespace sewer3d {

struct TriangulationOptions {
  /// Depth range searched along each camera ray: the working range (75–225 mm) with margin.
  /// Its disparity must stay below the array's width (the default module: 191 of 200
  /// columns), or two tiles fit one ray.
  double z_min_mm = 65.0;
  double z_max_mm = 250.0;
  /// Distance of the camera spot from the chosen element's epipolar line: at least this...
  double max_reprojection_px = 1.0;
  /// ...or, where the frame's spots lie farther from their lines (a real module's speckle,
  /// its projector's element placement, the wall's relief scatter them; its calibration error
  /// offsets them), their median distance plus their robust spread about it, scaled so that
  /// spots without offset get this many sigmas of their scatter; up to max_adaptive_px. A
  /// spread beyond that keeps the fixed limit (the frame does not fit the module). 0: the
  /// fixed limit alone.
  double adaptive_sigmas = 4.0;
  double max_adaptive_px = 5.0;
  void Check() const;
};

struct TriangulatedPoint {
  int observation = 0;         ///< index into the observations
  Eigen::Vector3d point_mm;    ///< camera frame
  int row = 0, col = 0;        ///< projector element (absolute)
  double reprojection_px = 0;  ///< worst of camera and projector
};

struct TriangulationStats {
  int unprojectable = 0;      ///< camera pixel beyond the lens's fold
  int no_element = 0;         ///< no tile of the decoded position fits the epipolar line
  int ambiguous = 0;          ///< more than one tile fits
  double tolerance_px = 0.0;  ///< epipolar limit used (TriangulationOptions, adaptive)
};

/// Triangulation for one module, with what depends only on the module computed once: the
/// undistorted projector coordinates of every element centre inside the projector image.
class Triangulator {
 public:
  Triangulator(const ModuleDescription& module, int array_rows, int array_cols,
               const TriangulationOptions& options);
  std::vector<TriangulatedPoint> Triangulate(const std::vector<CodedObservation>& observations,
                                             TriangulationStats* stats) const;
  /// Camera pixel `camera_px` triangulated with projector element (r, c) (absolute): the point
  /// when it lies within the depth range and both reprojections within `gate_px`, else none.
  /// `observation` is copied into the result.
  std::optional<TriangulatedPoint> AtElement(int r, int c, const Eigen::Vector2d& camera_px,
                                             double gate_px, int observation) const;

 private:
  const Eigen::Vector2d* Element(int r, int c) const;
  /// AtElement with the camera pixel's normalised coordinates `xy` already unprojected.
  std::optional<TriangulatedPoint> AtElement(int r, int c, const Eigen::Vector2d& camera_px,
                                             const Eigen::Vector2d& xy, double gate_px,
                                             int observation) const;
  /// The tile of one observation nearest its epipolar line (within `gate` px) and the
  /// distance of the second nearest.
  struct Candidates {
    bool projectable = false;
    TriangulatedPoint best;
    double second_px = 1e300;
  };
  Candidates NearestTiles(int k, const CodedObservation& o, double gate) const;

  ModuleDescription module_;
  int array_rows_, array_cols_;
  TriangulationOptions options_;
  CameraModel camera_, projector_;
  Eigen::Matrix<double, 3, 4> p_projector_;
  int element_rows_ = 0, element_cols_ = 0;
  std::vector<Eigen::Vector2d> element_xy_;  ///< NaN: outside the image or beyond the fold
};

/// One-off: Triangulator(module, ...).Triangulate(observations, stats).
std::vector<TriangulatedPoint> TriangulateObservations(
    const ModuleDescription& module, int array_rows, int array_cols,
    const std::vector<CodedObservation>& observations, const TriangulationOptions& options,
    TriangulationStats* stats);

/// Depth-outlier rejection: a wrong decode lands tens of millimetres off the surface, while real
/// steps (joints) are a few millimetres.
struct DepthOutlierOptions {
  double radius_px = 30.0;   ///< image neighbours compared with
  double min_step_mm = 5.0;  ///< depth differences up to max(min_step_mm, fraction · z) pass
  double fraction = 0.05;
  /// Surface segments (points joined through image neighbours whose depths pass the test
  /// above) of fewer points are removed: a spot group decoded with a wrong tile lies tens of
  /// millimetres off its surroundings, and where spots are sparse its few members are each
  /// other's majority. 0: none removed.
  int min_segment_points = 5;
  void Check() const;
};

/// Removes points whose depth disagrees with the median depth of their image neighbours
/// (within `radius_px`) by more than max(min_step_mm, fraction · z), points with fewer than
/// two neighbours, then the segments of fewer than `min_segment_points` points. Returns the
/// number removed.
int RejectDepthOutliers(std::vector<TriangulatedPoint>& points,
                        const std::vector<CodedObservation>& observations,
                        const DepthOutlierOptions& options = {});

/// Removes every point whose projector element another point also claims: an element lights
/// one spot, so of two spots decoded as the same element at least one is wrong (a label
/// slipped across a depth step) or both are fragments of one spot split by an edge, their
/// centres off. Returns the number removed.
int RejectSharedElements(std::vector<TriangulatedPoint>& points);

struct InconsistentPoints {
  int depth_outliers = 0;   ///< RejectDepthOutliers
  int shared_elements = 0;  ///< RejectSharedElements
};

/// RejectDepthOutliers, then RejectSharedElements: a wrong claim that is also a depth outlier
/// goes first, so the spot whose element it claimed keeps its point (the other order drops
/// both).
InconsistentPoints RejectInconsistentPoints(std::vector<TriangulatedPoint>& points,
                                            const std::vector<CodedObservation>& observations,
                                            const DepthOutlierOptions& options = {});

}  // namespace sewer3d
