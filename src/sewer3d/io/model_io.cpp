#include "sewer3d/io/model_io.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/input_file.hpp"
#include "sewer3d/io/ply_io.hpp"
#include "sewer3d/model/mesh.hpp"

namespace sewer3d {
namespace {

ModelMapFiles MapFilesWithPrefix(const std::filesystem::path& dir, const std::string& prefix) {
  return {dir / (prefix + "texture.png"),       dir / (prefix + "displacement.png"),
          dir / (prefix + "displacement.tiff"), dir / (prefix + "coverage.png"),
          dir / (prefix + "samples.png"),       dir / (prefix + "displacement_view.png"),
          dir / (prefix + "surface.ply")};
}

template <typename Mat>
void WriteImageAtomically(const std::filesystem::path& path, const Mat& image) {
  WriteFileAtomically(path, [&](const std::filesystem::path& t) { WriteImage(t, image); });
}

template <typename Mat>
Mat ReadTyped(const std::filesystem::path& path, int type, const MapGrid& grid, const char* what) {
  cv::Mat image = ReadImage(path, cv::IMREAD_UNCHANGED);
  if (image.type() != type) throw FileError(path, std::string("not a ") + what);
  if (image.rows != grid.rows || image.cols != grid.cols) {
    throw FileError(path, "size " + std::to_string(image.cols) + " x " +
                              std::to_string(image.rows) + " is not the map's " +
                              std::to_string(grid.cols) + " x " + std::to_string(grid.rows));
  }
  return image;
}

int RowsFrom(const MapGrid& run_grid, const MapGrid& tile_grid) {
  const double rows = (tile_grid.station0_mm - run_grid.station0_mm) / run_grid.resolution_mm;
  const int row0 = static_cast<int>(std::lround(rows));
  SEWER3D_CHECK(std::abs(rows - row0) < 1e-6 && row0 >= 0 &&
                    row0 + tile_grid.rows <= run_grid.rows && tile_grid.cols == run_grid.cols &&
                    std::abs(tile_grid.resolution_mm - run_grid.resolution_mm) < 1e-12,
                "tile at row " << rows << " of " << tile_grid.rows << " rows is not in the run's "
                               << run_grid.rows);
  return row0;
}

// The whole run's maps from its tiles (each tile's rows copied into place).
PipeMaps AssembleTiles(const std::filesystem::path& model_dir, const PipeModelInfo& info) {
  const MapGrid& g = info.grid;
  PipeMaps maps{g, cv::Mat3b(g.rows, g.cols, cv::Vec3b(0, 0, 0)),
                cv::Mat1f(g.rows, g.cols, std::numeric_limits<float>::quiet_NaN()),
                cv::Mat1w(g.rows, g.cols, std::uint16_t{0}),
                cv::Mat1b(g.rows, g.cols, std::uint8_t{0})};
  std::vector<int> covered(g.rows, 0);
  for (const ModelTile& t : info.tiles) {
    SEWER3D_CHECK(t.row0 >= 0 && t.rows > 0 && t.row0 + t.rows <= g.rows);
    MapGrid tile_grid = g;
    tile_grid.station0_mm = g.station0_mm + t.row0 * g.resolution_mm;
    tile_grid.rows = t.rows;
    const PipeMaps tile = ReadMapFiles(TileMapFiles(model_dir, t.index), tile_grid);
    const cv::Range rows(t.row0, t.row0 + t.rows);
    tile.texture.copyTo(maps.texture.rowRange(rows));
    tile.displacement_mm.copyTo(maps.displacement_mm.rowRange(rows));
    tile.samples.copyTo(maps.samples.rowRange(rows));
    tile.coverage.copyTo(maps.coverage.rowRange(rows));
    for (int r = t.row0; r < t.row0 + t.rows; ++r) ++covered[r];
  }
  SEWER3D_CHECK(std::all_of(covered.begin(), covered.end(), [](int n) { return n == 1; }),
                "the tiles must cover the run's rows once each");
  return maps;
}

// FileError unless the PNG at `path` declares grid.cols x grid.rows in its header.
void CheckPngSize(const std::filesystem::path& path, const MapGrid& grid) {
  CheckInputFile(path);
  std::array<char, 64> head{};
  std::ifstream in(path, std::ios::binary);
  in.read(head.data(), head.size());
  const std::vector<std::uint8_t> bytes(head.begin(), head.begin() + in.gcount());
  const auto size = ImageHeaderSize(bytes);
  if (!size) throw FileError(path, "not a PNG image (its header is not one)");
  if (size->width != static_cast<std::uint64_t>(grid.cols) ||
      size->height != static_cast<std::uint64_t>(grid.rows)) {
    throw FileError(path, "size " + std::to_string(size->width) + " x " +
                              std::to_string(size->height) + " is not the map's " +
                              std::to_string(grid.cols) + " x " + std::to_string(grid.rows));
  }
}

}  // namespace

void CheckMapFileSizes(const std::filesystem::path& model_dir, const PipeModelInfo& info) {
  const auto check = [](const ModelMapFiles& files, const MapGrid& grid) {
    for (const auto* path : {&files.texture, &files.coverage, &files.samples})
      CheckPngSize(*path, grid);
  };
  if (info.whole_maps) {
    check(WholeMapFiles(model_dir), info.grid);
    return;
  }
  for (const ModelTile& t : info.tiles) {
    MapGrid tile_grid = info.grid;
    tile_grid.rows = t.rows;
    check(TileMapFiles(model_dir, t.index), tile_grid);
  }
}

cv::Mat3b DisplacementView(const cv::Mat1f& displacement_mm, double range_mm) {
  cv::Mat3b view(displacement_mm.size(), cv::Vec3b(0, 0, 0));
  for (int r = 0; r < view.rows; ++r) {
    for (int c = 0; c < view.cols; ++c) {
      const float d = displacement_mm(r, c);
      if (!std::isfinite(d)) continue;
      const double t = std::clamp(d / range_mm, -1.0, 1.0);
      const auto fade = cv::saturate_cast<std::uint8_t>(255.0 * (1.0 - std::abs(t)));
      view(r, c) = t < 0.0 ? cv::Vec3b(255, fade, fade) : cv::Vec3b(fade, fade, 255);  // BGR
    }
  }
  return view;
}

void DisplacementEncoding::Check() const {
  ValidatePositive("displacement_png.scale_mm", scale_mm);
  SEWER3D_VALIDATE(std::isfinite(offset_mm), "displacement_png.offset_mm",
                   "must be finite, got " << offset_mm);
}

std::uint16_t DisplacementEncoding::Encode(float displacement_mm) const {
  if (!std::isfinite(displacement_mm)) return 0;
  const double v = std::round((displacement_mm - offset_mm) / scale_mm);
  return static_cast<std::uint16_t>(std::clamp(v, 1.0, 65535.0));
}

float DisplacementEncoding::Decode(std::uint16_t value) const {
  if (value == 0) return std::numeric_limits<float>::quiet_NaN();
  return static_cast<float>(offset_mm + value * scale_mm);
}

void ModelFileOptions::Check() const {
  encoding.Check();
  ValidatePositive("view_range_mm", view_range_mm);
  ValidateNotNegative("max_whole_cells", static_cast<double>(max_whole_cells));
}

ModelMapFiles WholeMapFiles(const std::filesystem::path& model_dir) {
  return MapFilesWithPrefix(model_dir, "");
}

ModelMapFiles TileMapFiles(const std::filesystem::path& model_dir, int tile_index) {
  return MapFilesWithPrefix(model_dir / "tiles", "tile_" + std::to_string(tile_index) + "_");
}

MapFilesReport WriteMapFiles(const ModelMapFiles& files, const PipeMaps& maps,
                             const Centreline& centreline, const ModelFileOptions& options) {
  options.Check();
  const cv::Size size(maps.grid.cols, maps.grid.rows);
  SEWER3D_CHECK(maps.texture.size() == size && maps.displacement_mm.size() == size &&
                maps.samples.size() == size && maps.coverage.size() == size);
  MapFilesReport report;
  cv::Mat1w code(size);
  for (int r = 0; r < size.height; ++r) {
    for (int c = 0; c < size.width; ++c) {
      const float d = maps.displacement_mm(r, c);
      code(r, c) = options.encoding.Encode(d);
      const double back = options.encoding.Decode(code(r, c));
      if (std::isfinite(d) && std::abs(back - d) > options.encoding.scale_mm)
        ++report.clipped_cells;
    }
  }
  WriteImageAtomically(files.texture, maps.texture);
  WriteImageAtomically(files.displacement_png, code);
  WriteImageAtomically(files.displacement_tiff, maps.displacement_mm);
  WriteImageAtomically(files.coverage, maps.coverage);
  WriteImageAtomically(files.samples, maps.samples);
  WriteImageAtomically(files.displacement_view,
                       DisplacementView(maps.displacement_mm, options.view_range_mm));
  const SurfacePoints surface = MapSurfacePoints(centreline, maps);
  report.surface_points = surface.points.size();
  WriteFileAtomically(files.surface, [&](const std::filesystem::path& t) {
    WritePly(t, surface.points, surface.colours_rgb, kModelFrame);
  });
  return report;
}

PipeMaps ReadMapFiles(const ModelMapFiles& files, const MapGrid& grid) {
  PipeMaps maps;
  maps.grid = grid;
  maps.texture = ReadTyped<cv::Mat3b>(files.texture, CV_8UC3, grid, "8-bit RGB image");
  maps.displacement_mm =
      ReadTyped<cv::Mat1f>(files.displacement_tiff, CV_32FC1, grid, "float32 one-channel map");
  maps.samples = ReadTyped<cv::Mat1w>(files.samples, CV_16UC1, grid, "16-bit grey image");
  maps.coverage = ReadTyped<cv::Mat1b>(files.coverage, CV_8UC1, grid, "8-bit grey image");
  for (const std::uint8_t v : maps.coverage) {
    if (v > static_cast<std::uint8_t>(Coverage::kFilled))
      throw FileError(files.coverage, "coverage value " + std::to_string(v) + " is not 0, 1 or 2");
  }
  return maps;
}

MapFilesReport WritePipeModel(const std::filesystem::path& model_dir, const Centreline& centreline,
                              const PipeMaps& maps, double start_station_mm,
                              const ModelFileOptions& options) {
  const MapFilesReport report = WriteMapFiles(WholeMapFiles(model_dir), maps, centreline, options);
  WriteModelJson(
      model_dir / "model.json",
      {centreline, maps.grid, start_station_mm, options.encoding, options.view_range_mm, true, {}});
  return report;
}

ModelTile WriteModelTile(const std::filesystem::path& model_dir, int tile_index,
                         const PipeMaps& tile, const MapGrid& run_grid,
                         const Centreline& centreline, const ModelFileOptions& options) {
  SEWER3D_CHECK(tile_index >= 0);
  const int row0 = RowsFrom(run_grid, tile.grid);
  WriteMapFiles(TileMapFiles(model_dir, tile_index), tile, centreline, options);
  return {tile_index, row0, tile.grid.rows};
}

bool ModelTileDone(const std::filesystem::path& model_dir, int tile_index) {
  return IsRegularFile(TileMapFiles(model_dir, tile_index).surface);
}

MapFilesReport FinishTiledModel(const std::filesystem::path& model_dir, PipeModelInfo info,
                                const ModelFileOptions& options) {
  options.Check();
  const auto cells = static_cast<std::int64_t>(info.grid.rows) * info.grid.cols;
  info.whole_maps = cells <= options.max_whole_cells;
  info.encoding = options.encoding;
  info.view_range_mm = options.view_range_mm;
  MapFilesReport report;
  if (info.whole_maps) {
    report = WriteMapFiles(WholeMapFiles(model_dir), AssembleTiles(model_dir, info),
                           info.centreline, options);
  }
  WriteModelJson(model_dir / "model.json", info);
  return report;
}

PipeModel ReadPipeModel(const std::filesystem::path& model_dir) {
  PipeModel model;
  model.info = ReadModelJson(model_dir / "model.json");
  model.maps = model.info.whole_maps ? ReadMapFiles(WholeMapFiles(model_dir), model.info.grid)
                                     : AssembleTiles(model_dir, model.info);
  return model;
}

}  // namespace sewer3d
