#pragma once
/// \file
/// module.json (DESIGN.md, module contract): validated loading and saving that preserves
/// fields this version does not know. Errors are FileError naming the file and the field.

#include <filesystem>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/pattern/binary_array.hpp"

namespace sewer3d {

struct LoadedModule {
  ModuleDescription module;
  BinaryArray pattern;                 ///< the matrix PNG the module names
  std::filesystem::path pattern_file;  ///< its path, resolved against the module file
};

/// Reads and validates a module file and its pattern matrix.
LoadedModule LoadModule(const std::filesystem::path& path);

/// Parses module JSON text; `path` is only used in messages and to resolve the pattern path.
/// Does not read the pattern matrix.
ModuleDescription ParseModule(const std::string& json_text, const std::filesystem::path& path);

/// Writes module.json. Fields of module.source_json that are not part of the contract are kept.
void SaveModule(const std::filesystem::path& path, const ModuleDescription& module);

/// The JSON text SaveModule writes.
std::string ModuleToJson(const ModuleDescription& module);

}  // namespace sewer3d
