#pragma once
/// \file
/// What the report's 3D viewer (viewer.js) draws: a dense cylinder following the centreline
/// whose vertices sit at the coarse cells' centres, pushed out by the coarse displacement
/// (glTF carries no displacement maps, so the relief is in the vertices), textured with the
/// report's texture picture.

#include <string>

#include "sewer3d/io/model_io.hpp"
#include "sewer3d/report/map_downsample.hpp"

namespace sewer3d {

/// The viewer's data as JSON text: radius_mm; rows and clocks of the vertex grid;
/// stations_mm and clocks_rad of the vertices; per row the frame (origin, crown, right, model
/// frame, mm) from the centreline; the displacement as base64 little-endian int16 in 0.01 mm
/// (−32768 = no data); and the texture picture's extent (station0_mm, station1_mm and the
/// share of the turn its height spans) for the texture coordinates. `relief` and `texture`
/// cover the whole run's grid (region rows 0 …, all columns).
std::string ViewerDataJson(const PipeModelInfo& info, const CoarseMaps& relief,
                           const CoarseMaps& texture);

}  // namespace sewer3d
