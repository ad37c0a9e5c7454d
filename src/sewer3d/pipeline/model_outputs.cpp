#include "sewer3d/pipeline/model_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/mesh_io.hpp"
#include "sewer3d/io/model_io.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;
constexpr int kMaxTextureSide = 8192;   // what browsers take (io/mesh_io.hpp)
constexpr int kPreviewLengthPx = 2400;  // preview.png along the pipe

void WriteImageAtomically(const std::filesystem::path& path, const cv::Mat& image) {
  WriteFileAtomically(path, [&](const std::filesystem::path& t) { WriteImage(t, image); });
}

/// Area-averaged copies of the tiles' texture and displacement view at `scale`, row by row.
struct SmallMaps {
  SmallMaps(const MapGrid& grid, double scale)
      : scale(scale),
        texture(std::max(1, static_cast<int>(std::lround(grid.rows * scale))),
                std::max(1, static_cast<int>(std::lround(grid.cols * scale))), cv::Vec3b(0, 0, 0)),
        view(texture.size(), cv::Vec3b(0, 0, 0)) {}
  void Add(const ModelTile& tile, const PipeMaps& maps, double view_range_mm) {
    const int r0 = static_cast<int>(std::lround(tile.row0 * scale));
    const int r1 =
        std::min(texture.rows, static_cast<int>(std::lround((tile.row0 + tile.rows) * scale)));
    if (r1 <= r0) return;
    const cv::Size size(texture.cols, r1 - r0);
    cv::resize(maps.texture, texture.rowRange(r0, r1), size, 0, 0, cv::INTER_AREA);
    cv::resize(DisplacementView(maps.displacement_mm, view_range_mm), view.rowRange(r0, r1), size,
               0, 0, cv::INTER_AREA);
  }
  double scale;
  cv::Mat3b texture, view;
};

/// preview.png for people: the unrolled pipe with the station along x (left = start) and the
/// clock down y (crown at the top), texture above the displacement view.
cv::Mat3b Preview(const SmallMaps& small) {
  const double f = std::min(1.0, static_cast<double>(kPreviewLengthPx) / small.texture.rows);
  const cv::Size size(std::max(1, static_cast<int>(std::lround(small.texture.cols * f))),
                      std::max(1, static_cast<int>(std::lround(small.texture.rows * f))));
  cv::Mat3b texture, view, out;
  cv::resize(small.texture, texture, size, 0, 0, cv::INTER_AREA);
  cv::resize(small.view, view, size, 0, 0, cv::INTER_AREA);
  cv::vconcat(texture.t(), view.t(), out);
  return out;
}

json GridJson(const MapGrid& g) {
  return {{"resolution_mm", g.resolution_mm},
          {"station0_mm", g.station0_mm},
          {"rows", g.rows},
          {"cols", g.cols}};
}

json CentrelineReportJson(const CentrelineFitReport& c) {
  json slices = json::array();
  for (const SliceReport& s : c.slices)
    slices.push_back({{"station_mm", s.station_mm},
                      {"radius_mm", s.radius_mm},
                      {"ovality_mm", s.ovality_mm},
                      {"rms_mm", s.rms_mm},
                      {"points", s.points},
                      {"used", s.used}});
  json j = {{"slices_used", c.slices_used},    {"slices_rejected", c.slices_rejected},
            {"fitted_radius_mm", c.radius_mm}, {"rms_mm", c.rms_mm},
            {"axis_rms_mm", c.axis_rms_mm},    {"iterations", c.iterations},
            {"last_move_mm", c.last_move_mm},  {"slices", slices}};
  j["bend_radius_mm"] = c.bend_radius_mm ? json(*c.bend_radius_mm) : json(nullptr);
  return j;
}

json ModuleOffsetsJson(const ModuleOffsets& m) {
  json j = {{"estimated", m.estimated},
            {"range_offset_mm", m.range_mm},
            {"seam_cells", m.pair_cells},
            {"cells", m.cells},
            {"seam_rms_before_mm", m.rms_before_mm},
            {"seam_rms_after_mm", m.rms_after_mm}};
  if (!m.estimated) j["why"] = m.why;
  return j;
}

}  // namespace

std::string ModelOptionsJson(const ModelStageOptions& o) {
  const json j = {{"resolution_mm", o.resolution_mm},
                  {"start_station_mm", o.start_station_mm},
                  {"nominal_diameter_mm", o.nominal_diameter_mm},
                  {"straight", o.straight},
                  {"tile_length_mm", o.tile_length_mm},
                  {"pixel_step", o.pixel_step},
                  {"feather_fraction", o.feather_fraction},
                  {"slice_spacing_mm", o.centreline.slice_spacing_mm},
                  {"smoothing_half_width_mm", o.centreline.smoothing_half_width_mm},
                  {"max_hole_mm", o.maps.max_hole_mm},
                  {"module_offsets", o.module_offsets},
                  {"mesh_step_mm", o.displaced.step_mm},
                  {"keep_tiles", o.keep_tiles}};
  return j.dump();
}

std::string ModelStageReportToJson(const ModelStageReport& r) {
  const json j = {{"ok", r.ok},
                  {"message", r.message},
                  {"acquisitions", r.acquisitions},
                  {"fit_points", r.fit_points},
                  {"centreline", CentrelineReportJson(r.centreline)},
                  {"nominal_diameter_mm", r.nominal_diameter_mm},
                  {"grid", GridJson(r.grid)},
                  {"splat_radius_mm", r.splat_radius_mm},
                  {"module_offsets", ModuleOffsetsJson(r.module_offsets)},
                  {"tiles", r.tiles},
                  {"tiles_from_earlier_run", r.tiles_from_earlier_run},
                  {"measured_fraction", r.measured_fraction},
                  {"filled_fraction", r.filled_fraction},
                  {"surface_points", r.surface_points},
                  {"whole_maps", r.whole_maps},
                  {"base_vertices", r.base_vertices},
                  {"displaced_vertices", r.displaced_vertices},
                  {"displaced_step_mm", r.displaced_step_mm},
                  {"seconds", r.seconds},
                  {"seconds_per_acquisition", r.seconds_per_acquisition},
                  {"threads", r.threads}};
  return j.dump(1);
}

void WriteModelReport(const std::filesystem::path& folder, const ModelStageReport& report) {
  WriteTextFileAtomically(folder / "report.json", ModelStageReportToJson(report) + "\n");
}

void WriteModelMeshes(const std::filesystem::path& folder, const PipeModelInfo& info,
                      const ModelStageOptions& options, ModelStageReport& report,
                      const ModelProgress& progress) {
  const MapGrid& grid = info.grid;
  SmallMaps small(grid, std::min({1.0, static_cast<double>(kMaxTextureSide) / grid.cols,
                                  static_cast<double>(kMaxTextureSide) / grid.rows}));
  // The mesh is never finer than the maps it samples (a finer lattice would find no cell).
  DisplacedMeshOptions mesh = options.displaced;
  mesh.step_mm = std::max(mesh.step_mm, options.resolution_mm);
  DisplacementDecimator lattice(grid, mesh);
  std::size_t measured = 0, filled = 0;
  int done = 0;
  for (const ModelTile& tile : info.tiles) {
    const PipeMaps maps =
        ReadMapFiles(TileMapFiles(folder, tile.index), grid.Tile(tile.row0, tile.rows));
    lattice.Add(maps);
    measured += static_cast<std::size_t>(cv::countNonZero(maps.coverage == 1));
    filled += static_cast<std::size_t>(cv::countNonZero(maps.coverage == 2));
    small.Add(tile, maps, info.view_range_mm);
    if (progress) progress("meshes", ++done, static_cast<int>(info.tiles.size()) + 1);
  }
  const double cells = static_cast<double>(grid.rows) * grid.cols;
  report.measured_fraction = static_cast<double>(measured) / cells;
  report.filled_fraction = static_cast<double>(filled) / cells;
  report.whole_maps = static_cast<std::int64_t>(cells) <= options.files.max_whole_cells;
  WriteImageAtomically(folder / "preview.png", Preview(small));

  const TriangleMesh base = BuildBaseCylinder(info.centreline, grid, options.base);
  report.base_vertices = base.positions.size();
  std::string texture_name = "texture.png";
  if (!report.whole_maps) {
    texture_name = "mesh_texture.png";
    WriteImageAtomically(folder / texture_name, small.texture);
  }
  WriteObj(folder / "mesh.obj", base, texture_name);
  const DisplacedMeshResult displaced = BuildDisplacedMesh(info.centreline, lattice);
  report.displaced_step_mm = displaced.step_mm;
  // Fewer than 24 vertices round the pipe draw a polygon, not a pipe with its relief.
  const double around_mm = grid.cols * grid.resolution_mm;
  if (constexpr int kMinAround = 24; displaced.step_mm * kMinAround > around_mm) {
    report.warnings.push_back(
        "mesh.glb: a vertex every " + std::to_string(std::lround(displaced.step_mm)) +
        " mm leaves about " + std::to_string(std::lround(around_mm / displaced.step_mm)) +
        " vertices round the pipe (" + std::to_string(std::lround(around_mm)) +
        " mm): a polygon without relief; --mesh-step-mm " +
        std::to_string(std::lround(around_mm / kMinAround)) + " or less keeps 24");
  }
  report.displaced_vertices = displaced.mesh.positions.size();
  if (displaced.within_budget && !displaced.mesh.positions.empty())
    WriteGlb(folder / "mesh.glb", displaced.mesh, small.texture);
  if (progress) progress("meshes", done + 1, done + 1);
}

}  // namespace sewer3d
