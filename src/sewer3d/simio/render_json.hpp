#pragma once
/// \file
/// Internal to simio/: the JSON forms shared by scene.json and scenario files (render options,
/// material names). Pulls in nlohmann/json through io/json_reader.hpp: .cpp files only.

#include <nlohmann/json.hpp>
#include <string>

#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/sim/scene.hpp"

namespace sewer3d {

/// The render options as JSON (what a scene.json or scenario file's "render" holds).
nlohmann::json RenderOptionsToJson(const RenderOptions& o);
/// Reads the members of a "render" object over `o` (absent members keep their values).
void ReadRenderOptions(const JsonReader& in, const nlohmann::json& j, const std::string& prefix,
                       RenderOptions& o);

const char* MaterialName(Material m);
/// Throws via `in` when the name is not a material.
Material ParseMaterial(const JsonReader& in, const std::string& name, const std::string& field);

}  // namespace sewer3d
