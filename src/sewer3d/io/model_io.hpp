#pragma once
/// \file
/// The pipe model's folder (DESIGN.md "processing workspace", WS/model/; paper §4.4):
///
/// - `texture.png` 8-bit RGB; `displacement.png` 16-bit, value v ↔ d = offset_mm + v · scale_mm,
///   0 = no data (scale and offset in model.json); `displacement.tiff` float32 mm, NaN = none;
///   `coverage.png` 8-bit, 0 none, 1 measured, 2 filled; `samples.png` 16-bit points per cell;
///   `displacement_view.png` for people (±range: inward blue, 0 white, outward red, none black);
///   `surface.ply` one point per covered cell with a displacement (model frame, colour);
/// - `model.json`, written last: how a pixel becomes a 3D point (grid, radius, conventions,
///   centreline samples, the PNG encoding) and which files hold the maps.
///
/// Long runs are written tile by tile with bounded memory: each tile's files go to
/// `tiles/tile_<k>_<name>` as soon as the tile is done; FinishTiledModel then writes the
/// whole-run files (assembled from the tiles) only when the run has at most
/// ModelFileOptions::max_whole_cells cells, and otherwise leaves the tiles as the maps
/// (model.json lists them; ReadPipeModel assembles them). Every file is written atomically;
/// errors are FileError "PATH: field: problem".

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

/// displacement.png's code: v = round((d − offset_mm) / scale_mm) clamped to 1 … 65535, 0 for
/// no data. The default covers ±65.5 mm in steps of 2 µm, d = 0 at v = 32768.
struct DisplacementEncoding {
  double scale_mm = 0.002;
  double offset_mm = -65.536;
  void Check() const;
  [[nodiscard]] std::uint16_t Encode(float displacement_mm) const;
  [[nodiscard]] float Decode(std::uint16_t value) const;  ///< NaN for 0
};

/// displacement_view.png's colours for people: inward (negative) blue, 0 white, outward red
/// (saturating at ±range_mm), no data black. BGR.
cv::Mat3b DisplacementView(const cv::Mat1f& displacement_mm, double range_mm);

struct ModelFileOptions {
  DisplacementEncoding encoding;
  double view_range_mm = 10.0;  ///< displacement_view.png saturates at ± this
  /// Whole-run map files only for runs up to this many cells (30 M ≈ 1.27 m of DN300 at
  /// 0.2 mm, about 1.2 GB to assemble them and their surface points); longer runs keep tiles.
  std::int64_t max_whole_cells = 30'000'000;
  void Check() const;
};

/// One tile of a tiled model: rows row0 … row0 + rows − 1 of the run's grid.
struct ModelTile {
  int index = 0;
  int row0 = 0;
  int rows = 0;
};

/// What model.json holds.
struct PipeModelInfo {
  Centreline centreline;  ///< with the model radius
  MapGrid grid;           ///< the whole run's
  double start_station_mm = 0.0;
  DisplacementEncoding encoding;
  double view_range_mm = 10.0;
  bool whole_maps = true;        ///< the whole-run map files exist
  std::vector<ModelTile> tiles;  ///< the tiles' files exist (empty for a model written whole)
};

/// The map files of the whole run (`prefix` "") or of a tile (`tiles/tile_<k>_`).
struct ModelMapFiles {
  std::filesystem::path texture, displacement_png, displacement_tiff, coverage, samples,
      displacement_view, surface;
};
ModelMapFiles WholeMapFiles(const std::filesystem::path& model_dir);
ModelMapFiles TileMapFiles(const std::filesystem::path& model_dir, int tile_index);

struct MapFilesReport {
  std::size_t surface_points = 0;  ///< cells with coverage and a displacement
  std::size_t clipped_cells = 0;   ///< displacements outside displacement.png's range
};

/// Writes the map files of `maps` (surface.ply last, so its presence means the set is
/// complete). `maps` must be consistent (all maps grid.rows × grid.cols).
MapFilesReport WriteMapFiles(const ModelMapFiles& files, const PipeMaps& maps,
                             const Centreline& centreline, const ModelFileOptions& options);

/// Reads the maps back (displacement from the TIFF, exactly) and checks their sizes
/// against `grid`.
PipeMaps ReadMapFiles(const ModelMapFiles& files, const MapGrid& grid);

/// FileError naming the first PNG map (texture, coverage, samples; whole or of a tile) that is
/// missing or whose header declares another size than model.json's grid: what ReadMapFiles would
/// refuse, found without decoding, so that a stage can refuse before it removes its earlier
/// outputs.
void CheckMapFileSizes(const std::filesystem::path& model_dir, const PipeModelInfo& info);

/// A run held whole: its map files, then model.json (info.grid = maps.grid, no tiles).
MapFilesReport WritePipeModel(const std::filesystem::path& model_dir, const Centreline& centreline,
                              const PipeMaps& maps, double start_station_mm,
                              const ModelFileOptions& options);

/// One tile of a tiled run (its grid a whole number of rows into `run_grid`): its map files.
ModelTile WriteModelTile(const std::filesystem::path& model_dir, int tile_index,
                         const PipeMaps& tile, const MapGrid& run_grid,
                         const Centreline& centreline, const ModelFileOptions& options);
/// True when the tile's files are complete (its surface.ply exists).
bool ModelTileDone(const std::filesystem::path& model_dir, int tile_index);

/// Ends a tiled run: the whole-run map files assembled from the tiles when the run has at most
/// options.max_whole_cells cells (info.whole_maps says which), then model.json. The tiles must
/// cover the run grid's rows without overlap.
MapFilesReport FinishTiledModel(const std::filesystem::path& model_dir, PipeModelInfo info,
                                const ModelFileOptions& options);

void WriteModelJson(const std::filesystem::path& path, const PipeModelInfo& info);
PipeModelInfo ReadModelJson(const std::filesystem::path& path);

struct PipeModel {
  PipeModelInfo info;
  PipeMaps maps;  ///< the whole run (assembled from the tiles when there are no whole files)
};
/// model.json and the maps of the model in `model_dir`.
PipeModel ReadPipeModel(const std::filesystem::path& model_dir);

}  // namespace sewer3d
