#pragma once
/// \file
/// One frame of one module from pattern image to 3D (DESIGN.md, processing chain steps 2–3):
/// decode the spot pattern, pick each spot's pattern tile on its epipolar line and triangulate
/// it (DLT), drop depth outliers, interpolate a depth map aligned with the camera image, and
/// colour the points from a texture image taken at the same instant.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/decode/decoder.hpp"
#include "sewer3d/pattern/binary_array.hpp"
#include "sewer3d/pattern/constraints.hpp"
#include "sewer3d/triangulate/correspondences.hpp"
#include "sewer3d/triangulate/cut_spots.hpp"
#include "sewer3d/triangulate/element_mesh.hpp"
#include "sewer3d/triangulate/lost_spots.hpp"

namespace sewer3d {

/// Options of every stage; the defaults are `sewer3d reconstruct`'s.
struct FrameReconstructionOptions {
  DecoderOptions decoder;              ///< binarisation, spots, lattice, codewords
  TriangulationOptions triangulation;  ///< depth range searched, reprojection limit
  DepthOutlierOptions outliers;        ///< RejectDepthOutliers
  CutSpotOptions cut_spots;            ///< spots a depth step cut (RejectCutSpots)
  LostSpotOptions lost_spots;          ///< spots the binariser missed (LostSpotFinder)
  /// Depth map: longest triangle edge, in pattern pitches (module.pattern.pitch_px each, taken
  /// as camera pixels). Longer edges span holes, depth steps or the border of the lit area.
  double max_edge_steps = 5.5;
  /// The depth map's triangles: false (default), the module's lit elements meshed
  /// (InterpolateDepthOnMesh), so a spot that gave no point leaves a hole: a joint's gap, a
  /// depth step's shadow band stay open instead of being bridged by a ramp. true: the Delaunay
  /// triangles of the frame's points (InterpolateDepth), which bridge lost spots.
  bool bridge_lost_spots = false;
  /// On the element mesh, a hole's surface drawn on to halfway toward the first lost spot
  /// (MeshDepthOptions::holes_to_midpoints, default); false: holes end at the last spots seen.
  bool holes_to_midpoints = true;
  /// A frame is not of this module's pattern as the module sees it (a mirrored or flipped
  /// image, another pattern) when, of at least `mismatch_min_decoded` decoded spots, more than
  /// `mismatch_off_epipolar_fraction` fit no tile on their epipolar line and under
  /// `mismatch_window_fraction` of the windows read decode: its chance points are dropped
  /// (FrameReport::not_of_module). Measured: flipped 2592 px frames 86–95 % off the line and
  /// 13–26 % of windows; the demo's frames at most 25 % off the line. A real frame that looks
  /// into a deep opening loses spots to the depth range, but its windows still decode.
  double mismatch_off_epipolar_fraction = 0.6;
  double mismatch_window_fraction = 0.5;
  int mismatch_min_decoded = 50;
  void Check() const;
};

/// A triangulated spot.
struct FramePoint {
  Eigen::Vector3d point_mm;   ///< camera frame
  Eigen::Vector2d camera_px;  ///< spot centre (pixel centres at integers)
  int row = 0, col = 0;       ///< projector element (absolute, not modulo the array)
  /// Red, green, blue of the texture at the nearest pixel; zero without a texture.
  std::array<std::uint8_t, 3> rgb{};
};

/// What happened to the spots of one frame (the fields of `sewer3d reconstruct`'s
/// report.json).
struct FrameReport {
  int spots_found = 0;        ///< spots detected in the pattern image
  int lattice_groups = 0;     ///< connected lattice groups (LatticeLabels::groups)
  int lattice_conflicts = 0;  ///< edges contradicting the labels (LatticeLabels::conflicts)
  int windows_read = 0;       ///< 6 x 6 windows read (CodewordStats)
  int windows_decoded = 0;    ///< of those, found in the codebook
  int bits_corrected = 0;     ///< single-bit corrections among them
  int spots_decoded = 0;      ///< spots with an array position
  /// Points from spots the binariser missed, found where the lattice put their elements
  /// (LostSpotFinder; counted in `points`).
  int lost_spots_found = 0;
  /// Spots found but not turned into points, by reason.
  struct Rejected {
    int votes_split_or_too_few = 0;     ///< decode: no position enough windows agree on
    int beyond_lens_fold = 0;           ///< camera pixel the lens model cannot unproject
    int no_tile_on_epipolar_line = 0;   ///< no tile of the decoded position fits
    int several_tiles_fit = 0;          ///< more than one tile fits
    int element_claimed_twice = 0;      ///< RejectSharedElements
    int cut_by_step = 0;                ///< RejectCutSpots
    int depth_outlier_or_isolated = 0;  ///< RejectDepthOutliers
    int not_of_module = 0;              ///< dropped with the whole frame (not_of_module)
  } rejected;
  /// The frame does not fit the module (FrameReconstructionOptions::mismatch_*): no points.
  bool not_of_module = false;
  /// Distance from the epipolar line up to which a tile fits (TriangulationOptions: the fixed
  /// limit, or the frame's own scatter times adaptive_sigmas).
  double epipolar_tolerance_px = 0.0;
  int points = 0;        ///< triangulated points kept
  int depth_pixels = 0;  ///< pixels of the depth map with a depth
  /// Wall-clock time of each stage.
  struct Seconds {
    double binarise = 0, spots = 0, lattice = 0, codewords = 0;
    double triangulate = 0;  ///< triangulation and outlier rejection
    double lost_spots = 0;   ///< LostSpotFinder
    double depth_map = 0;    ///< colours and depth interpolation
  } seconds;
};

/// One frame's points, depth map and report.
struct FrameReconstruction {
  std::vector<FramePoint> points;  ///< in the order of the decoded spots
  bool coloured = false;           ///< a texture was given: `rgb` of the points is set
  /// z (mm, camera frame) at every camera pixel inside the triangulated spot mesh; NaN
  /// elsewhere. Camera image size.
  cv::Mat1f depth_mm;
  FrameReport report;
};

/// Why a frame with FrameReport::not_of_module was refused, in words.
std::string NotOfModuleReason(const FrameReport& report);

/// Why a frame gave no point, in words: no spot decoded ("no spot pattern decoded (N spots
/// found, 0 decoded)"), or decoded spots of which none fit a tile on its epipolar line (an
/// image shifted, rotated or scaled against the module's calibration, or of another module).
std::string NoPointsReason(const FrameReport& report);

/// What makes a frame's points doubtful though some were made, in words (empty: nothing):
/// points but no pixel of depth (the longest triangle edge allowed is too short),
/// fewer than half of 50 or more spots decoded (spots too small or too close for the camera),
/// or fewer than half of the decoded spots triangulated (their disparities outside the
/// module's working range: an image of another module). A frame of a plain wall has over 90 %
/// of both; one looking into a connection's bore in the demo run 71 % triangulated.
std::string FrameDoubt(const FrameReport& report, std::size_t points);

/// The single-frame chain for one module, with everything that depends only on the module
/// (decoder lattice prediction and buffers, projector element centres) built once: a run
/// reconstructs thousands of frames per module.
class FrameReconstructor {
 public:
  /// `pattern` is the module's matrix, `constraints` those it satisfies (InferConstraints);
  /// throws std::invalid_argument on invalid options or module.
  FrameReconstructor(const ModuleDescription& module, const BinaryArray& pattern,
                     const PatternConstraints& constraints,
                     const FrameReconstructionOptions& options = {});

  /// `pattern_image`: grey, 8- or 16-bit (CV_8UC1 or CV_16UC1), the module's camera size.
  /// `texture_bgr`: null, or the texture image of the same instant (OpenCV's BGR order, same
  /// size) that colours the points. A frame where nothing decodes gives zero points and an
  /// all-NaN depth map; a wrong image type or size throws std::invalid_argument.
  FrameReconstruction Reconstruct(const cv::Mat& pattern_image,
                                  const cv::Mat3b* texture_bgr = nullptr);

 private:
  ModuleDescription module_;
  FrameReconstructionOptions options_;
  Decoder decoder_;
  Triangulator triangulator_;
  ElementMesh mesh_;
  NeighbourLists mesh_neighbours_;  // for RejectCutSpots
  LostSpotFinder lost_spots_;
  std::vector<int> spot_areas_;          // per observation, reused between frames
  std::vector<Eigen::Vector2d> pixels_;  // depth-map buffers, reused between frames
  std::vector<double> depths_;
  std::vector<Eigen::Vector2i> elements_;
};

/// One-off: FrameReconstructor(module, pattern, constraints, options).Reconstruct(...).
FrameReconstruction ReconstructFrame(const ModuleDescription& module, const BinaryArray& pattern,
                                     const PatternConstraints& constraints,
                                     const cv::Mat& pattern_image, const cv::Mat3b* texture_bgr,
                                     const FrameReconstructionOptions& options = {});

}  // namespace sewer3d
