#pragma once
/// \file
/// The model stage (issue 16; paper §4.4; DESIGN.md contract "processing workspace";
/// docs/model.md): the registered RGB-D acquisitions become the pipe model.
/// 1. Samples of every acquisition's depth map (WS/rgbd) moved into the model frame by its
///    registered pose (WS/registration/poses.csv) → the centreline fit (model/centreline_fit).
/// 2. The (station, clock) grid at `resolution_mm` over the stations the acquisitions cover,
///    cut into tiles along the pipe; per tile, every pixel with depth of each acquisition that
///    reaches it is unrolled into a MapAccumulator (weight: depth noise × feathering toward
///    the image border), then the tile's files are written (resumable: done tiles are kept).
/// 3. The whole-run map files and model.json (io/model_io), the base cylinder (mesh.obj +
///    mesh.mtl, the texture.png) and the displaced mesh (mesh.glb), report.json; the tiles
///    are removed when the whole-run files hold the maps (unless keep_tiles).

#include <Eigen/Core>
#include <functional>
#include <string>

#include "sewer3d/io/model_io.hpp"
#include "sewer3d/model/centreline_fit.hpp"
#include "sewer3d/model/map_accumulator.hpp"
#include "sewer3d/model/mesh.hpp"
#include "sewer3d/model/module_offsets.hpp"
#include "sewer3d/pipeline/workspace.hpp"
#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

struct ModelStageOptions {
  double resolution_mm = 0.2;     ///< map cell (paper: 0.2 mm)
  double start_station_mm = 0.0;  ///< station of the run's first carrier position
  /// Model radius = half of this; 0: the fitted diameter rounded to 5 mm (nominal sizes).
  double nominal_diameter_mm = 0.0;
  bool straight = false;          ///< one straight cylinder instead of a bending centreline
  double tile_length_mm = 100.0;  ///< tile along the pipe (memory: ~22 bytes per cell)
  int fit_samples_per_acquisition = 3000;  ///< depth samples each gives the centreline fit
  int pixel_step = 1;                      ///< every n-th pixel (rows, columns) into the maps
  double feather_fraction = 0.08;          ///< border ramp, as a fraction of the image width
  double depth_sigma_ref_mm = 0.03;        ///< DepthWeight: σ at depth_ref_mm
  double depth_ref_mm = 150.0;
  CentrelineFitOptions centreline;  ///< its nominal diameter and start station set by the stage
  /// Its splat_radius_mm 0 = automatic: where a pixel's footprint on the wall (depth_ref_mm /
  /// f · pixel_step) exceeds 0.7 cells, each pixel is splatted over that radius so the map has
  /// no holes between pixels (reduced-size cameras); otherwise nearest cell. Its
  /// hole_edge_band_mm 5: hole edges at the frames' median, as the rgbd stage draws each
  /// frame's holes to the midpoints toward its lost spots (docs/rgbd.md).
  MapAccumulatorOptions maps{.hole_edge_band_mm = 5.0};
  /// Each module's range offset from the seams (model/module_offsets.hpp), taken off its
  /// pixels' ranges before they go into the maps; false: none.
  bool module_offsets = true;
  ModuleOffsetOptions offsets;
  ModelFileOptions files;
  BaseCylinderOptions base;
  DisplacedMeshOptions displaced;
  /// Keep WS/model/tiles/ after the whole-run files are written (they duplicate them; a run
  /// too long for whole-run files always keeps its tiles, which are then the maps).
  bool keep_tiles = false;
  int threads = 1;  ///< tiles accumulated at once
  bool force = false;

  void Check() const;
};

/// The options that decide the outputs, as workspace.json records them.
std::string ModelOptionsJson(const ModelStageOptions& options);

struct ModelStageReport {
  bool ok = false;      ///< false: the model could not be made (message says why)
  std::string message;  ///< why not, one line
  /// What the stage found doubtful in its inputs but used (one line each), e.g. a poses.csv
  /// that is not the one the register stage wrote.
  std::vector<std::string> warnings;
  int acquisitions = 0;  ///< registered ones with depth
  int fit_points = 0;
  CentrelineFitReport centreline;
  double nominal_diameter_mm = 0.0;
  MapGrid grid;
  double splat_radius_mm = 0.0;  ///< as used
  ModuleOffsets module_offsets;  ///< as taken off (all zero when off or not estimated)
  int tiles = 0, tiles_from_earlier_run = 0;
  double measured_fraction = 0.0, filled_fraction = 0.0;  ///< of the grid's cells
  std::size_t surface_points = 0;
  bool whole_maps = true;
  std::size_t base_vertices = 0, displaced_vertices = 0;
  double displaced_step_mm = 0.0;
  double seconds = 0.0, seconds_per_acquisition = 0.0;
  int threads = 1;
};

std::string ModelStageReportToJson(const ModelStageReport& report);

/// Progress of the passes ("samples", "tiles", "meshes"), never from two threads at once.
using ModelProgress = std::function<void(const std::string& pass, int finished, int total)>;

/// Runs the model stage of `run` into `workspace`. Throws std::invalid_argument on invalid
/// options, WorkspaceConflict, FileError when inputs (registration, rgbd) are missing or
/// unreadable; a model that cannot be made (too few slices) gives report.ok = false.
ModelStageReport RunModelStage(const CaptureRun& run, Workspace& workspace,
                               const ModelStageOptions& options,
                               const ModelProgress& progress = {});

/// Whether `model_dir` still holds every file the model stage wrote there: model.json, the
/// maps it names (whole or tiles), mesh.obj / .mtl (and mesh_texture.png for a tiled model),
/// preview.png and report.json. `process` redoes a model recorded done when one is gone.
bool ModelFilesPresent(const std::filesystem::path& model_dir);

}  // namespace sewer3d
