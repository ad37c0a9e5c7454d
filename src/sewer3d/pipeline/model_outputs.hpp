#pragma once
/// \file
/// The model stage's outputs besides the maps (model_stage.hpp): the base cylinder (mesh.obj +
/// mesh.mtl on the texture map), the displaced mesh (mesh.glb with a texture a browser takes),
/// report.json, and the options as workspace.json records them.

#include <filesystem>

#include "sewer3d/pipeline/model_stage.hpp"

namespace sewer3d {

/// Reads the tiles back one at a time (bounded memory) into the displaced mesh's lattice and
/// a texture of at most 8192 px a side; writes mesh.obj/.mtl (on texture.png when the whole
/// maps exist, else on mesh_texture.png, written then) and mesh.glb. Fills the report's mesh
/// figures.
void WriteModelMeshes(const std::filesystem::path& folder, const PipeModelInfo& info,
                      const ModelStageOptions& options, ModelStageReport& report,
                      const ModelProgress& progress);

void WriteModelReport(const std::filesystem::path& folder, const ModelStageReport& report);

}  // namespace sewer3d
