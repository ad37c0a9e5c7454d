#pragma once
/// \file
/// Meshes of the pipe model as files (DESIGN.md "processing workspace": mesh.obj + mesh.mtl,
/// mesh.glb): Wavefront OBJ with its material file for MeshLab and Blender, and binary glTF 2.0
/// (GLB) with the texture embedded, for browsers. Both written atomically; errors are FileError.

#include <cstdint>
#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "sewer3d/model/mesh.hpp"

namespace sewer3d {

/// Writes `path_obj` (positions in mm in the model frame, UVs, normals, one material) and the
/// material file beside it (same name, `.mtl`) whose map_Kd is `texture_file_name`, relative to
/// the OBJ's folder (e.g. "texture.png"). OBJ's v runs up the image, so vt = (u, 1 − v).
void WriteObj(const std::filesystem::path& path_obj, const TriangleMesh& mesh,
              const std::string& texture_file_name);

/// Writes a GLB: one mesh of one primitive (POSITION with min/max, NORMAL, TEXCOORD_0, uint32
/// indices), its material's base colour the embedded PNG `texture_png` (bytes of a PNG file),
/// double-sided, not metallic. glTF is in metres with y up: the node scales mm to m and turns
/// the model frame (y down) half a turn about x.
void WriteGlb(const std::filesystem::path& path, const TriangleMesh& mesh,
              const std::vector<std::uint8_t>& texture_png);

/// The same with the texture from an image (BGR), encoded as PNG after shrinking it (area
/// average) to at most `max_texture_side_px` on each side: browsers refuse larger textures
/// (8192 is widely supported; the UVs are unaffected).
void WriteGlb(const std::filesystem::path& path, const TriangleMesh& mesh,
              const cv::Mat3b& texture_bgr, int max_texture_side_px = 8192);

}  // namespace sewer3d
