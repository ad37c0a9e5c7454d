#pragma once
/// \file
/// Dense depth aligned with the camera image from the sparse spot points: inverse depth 1/z
/// interpolated linearly (barycentric weights) inside the Delaunay triangles of the spot
/// centres — for a plane seen by a pinhole camera 1/z is an affine function of the pixel, so
/// the map is exact there, where linear z would bulge; triangles with an edge longer than
/// max_edge_px (holes, depth steps, the border of the lit area) stay empty (NaN).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "sewer3d/triangulate/element_mesh.hpp"

namespace sewer3d {

/// `pixels[i]` is the camera position of a point with depth `depths_mm[i]` (> 0). Pixels
/// outside the image are ignored; pixel centres at integers.
cv::Mat1f InterpolateDepth(cv::Size image_size, const std::vector<Eigen::Vector2d>& pixels,
                           const std::vector<double>& depths_mm, double max_edge_px);

/// How InterpolateDepthOnMesh draws a frame's map.
struct MeshDepthOptions {
  /// A triangle with a camera edge longer than this stays empty (holes, depth steps).
  double max_edge_px = 0.0;
  /// An edge joining elements farther apart than this in the pattern (elements; where the
  /// pattern is sparse, its Delaunay edges reach 5–6) may be longer in the camera in
  /// proportion: max_edge_px × distance / this. Without it the sparse places' triangles
  /// fail the limit wherever the wall is seen stretched, leaving rows of holes at the same
  /// image positions in every frame. 0: the plain limit for every edge.
  double long_edge_elements = 4.0;
  /// Radius of the disc drawn for a point that is the corner of no filled triangle.
  double spot_radius_px = 0.0;
  /// Where a lost spot's triangle meets a filled one, the surface is drawn on to halfway
  /// toward the lost spot (its camera position and depth extrapolated from the filled
  /// triangle; a triangle that meets the surface only at a corner, toward its two lost spots
  /// from that corner): a surface ends somewhere between the last spot seen and the first one lost,
  /// so one frame's hole drawn from the last spot seen is too wide by about half a triangle
  /// on each side. A model that kept every cell any frame measured (the union of the
  /// frames' surfaces) would then make holes too narrow; the model stage puts a hole's edge
  /// at the frames' median instead (MapAccumulatorOptions::hole_edge_band_mm, docs/rgbd.md).
  bool holes_to_midpoints = true;
};

/// Depth over a module's element mesh: point i shows element `elements[i]` (row, column) at
/// camera pixel `pixels[i]` with depth `depths_mm[i]`. A mesh triangle is filled where its
/// three elements have points, none of its camera edges is longer than max_edge_px, and its
/// camera image keeps the orientation most of the frame's triangles have: one folded over (a
/// depth step whose far side the camera sees shifted past the near side's spots) stays empty.
/// Spots lost anywhere leave holes here where InterpolateDepth bridges them (drawn to the
/// midpoints, MeshDepthOptions::holes_to_midpoints). A point that is the corner of no filled
/// triangle (on a surface too narrow for a triangle of its own: an intruding pipe's rim) gets
/// a disc of `spot_radius_px` at its depth, on pixels nothing else filled; where no triangle
/// is filled at all, nothing is.
cv::Mat1f InterpolateDepthOnMesh(cv::Size image_size, const ElementMesh& mesh,
                                 const std::vector<Eigen::Vector2i>& elements,
                                 const std::vector<Eigen::Vector2d>& pixels,
                                 const std::vector<double>& depths_mm,
                                 const MeshDepthOptions& options);

/// The pixels of a depth map that hold a depth (not NaN).
int CountDepthPixels(const cv::Mat1f& depth_mm);

}  // namespace sewer3d
