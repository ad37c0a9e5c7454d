#pragma once
/// \file
/// Scene JSON (docs/simulator.md) and the files of a rendered frame. Errors are FileError.

#include <filesystem>
#include <string>

#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/sim/scene.hpp"

namespace sewer3d {

/// Parses a scene JSON document; `path` names the source in messages.
Scene ParseScene(const std::string& json_text, const std::filesystem::path& path);
/// Reads a scene file, or the scene.json of a rendered frame (whose "scene" member it uses).
Scene ReadScene(const std::filesystem::path& path);
std::string SceneToJson(const Scene& scene);
/// A scene file's "render" member (a rendered frame's scene.json has one) read over `options`;
/// false (options unchanged) when the file has none. FileError naming the field when invalid.
bool ReadSceneRenderOptions(const std::filesystem::path& path, RenderOptions& options);
/// The module a rendered frame's scene.json names (its "module" member, relative to the file's
/// folder), as a path to open from here; empty when the file names none. FileError when the
/// member is not a string.
std::string ReadSceneModule(const std::filesystem::path& path);

/// The pattern image as stored: 8-bit grey, or 16-bit holding the DN when bits > 8.
void WritePatternImage(const std::filesystem::path& path, const RenderedFrame& frame, int bits);
/// The texture image as stored: 8-bit colour (BGR file order); with a Bayer filter
/// (frame.texture_raw) one-channel raw, 8-bit when `bits` is 8, else 16-bit holding the DN.
void WriteTextureImage(const std::filesystem::path& path, const RenderedFrame& frame, int bits);

/// Writes pattern.png (8-bit, or 16-bit holding the DN when bits > 8), texture.png (8-bit
/// colour), truth_depth.tiff (float32 z mm, NaN where no surface), depth_preview.png, and
/// scene.json (the scene exactly as rendered, the render options, the seed, the module path).
void WriteRenderedFrame(const std::filesystem::path& dir, const RenderedFrame& frame,
                        const Scene& scene, const RenderOptions& options,
                        const std::filesystem::path& module_path);

}  // namespace sewer3d
