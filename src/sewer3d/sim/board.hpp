#pragma once
/// \file
/// A printed checkerboard on a flat plate, for calibration captures (docs/calibration.md):
/// the surface seen by the renderer, and random poses that show the whole board to both the
/// camera and the projector.

#include <cstdint>
#include <vector>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/sim/surface.hpp"

namespace sewer3d {

/// Inner corners cols x rows at square_mm pitch, (i, j) at (j · s, i · s, 0) in the board
/// frame (as BoardCorners); squares of albedo 0.05 and 0.85 alternate over
/// [−s, cols · s] x [−s, rows · s]; a white margin surrounds them; nothing beyond the plate.
struct Checkerboard {
  int cols = 9, rows = 6;
  double square_mm = 10.0;
  double margin_mm = 10.0;
  void Check() const;
};

class BoardSurface final : public Surface {
 public:
  BoardSurface(const Checkerboard& board, const Rigid3d& camera_from_board)
      : board_(board),
        camera_from_board_(camera_from_board),
        board_from_camera_(camera_from_board.Inverse()) {}
  std::optional<SurfaceHit> Intersect(const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction) const override;
  std::uint64_t MaterialSeed() const override { return 0; }

 private:
  Checkerboard board_;
  Rigid3d camera_from_board_, board_from_camera_;
};

struct BoardPoseOptions {
  double distance_min_mm = 90.0, distance_max_mm = 200.0;  ///< board centre along the view
  double max_tilt_deg = 35.0;  ///< between the board normal and the camera's optical axis
  double margin_px = 20.0;     ///< corners this far inside camera and projector images
  /// A square must look at least this large at distance_max_mm, or no checkerboard detector
  /// finds the board (0.1 mm squares rendered a board of a few pixels).
  double min_square_px = 8.0;
};

/// `count` random poses (deterministic for a seed) with every inner corner inside both the
/// camera and the projector image; throws InvalidValue ("square_mm") when a square would look
/// smaller than options.min_square_px, ("board") when no such poses can be found.
std::vector<Rigid3d> RandomBoardPoses(const ModuleDescription& module, const Checkerboard& board,
                                      int count, std::uint64_t seed,
                                      const BoardPoseOptions& options = {});

}  // namespace sewer3d
