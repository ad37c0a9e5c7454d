#pragma once
/// \file
/// Atomic file writes: a file is written under a temporary name in its own folder and renamed
/// over its final name only when complete, so a reader (or a resumed run after a kill) sees
/// either the old file, or nothing, or the whole new file, never a part of one. Errors are
/// FileError naming the final path.

#include <filesystem>
#include <functional>
#include <string>

namespace sewer3d {

/// Calls `write(temporary)` with a fresh path in `path`'s folder (created when missing) that
/// keeps `path`'s extension (writers choose the format from it: `.png`, `.tiff`), then renames
/// the temporary over `path`. If `write` throws, the temporary is removed and the exception
/// passes on; `path` is left as it was. A temporary left by a killed process is named
/// `.<file name>.tmp-<pid>-<n><extension>` and is never read.
void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path&)>& write);

/// A fresh name beside `path` for a temporary file or folder: `.<file name>.tmp-<pid>-<n>` +
/// `path`'s extension; unique within and across processes. Nothing is created.
std::filesystem::path TemporaryPathFor(const std::filesystem::path& path);

/// WriteTextFile (text_file.hpp) through WriteFileAtomically.
void WriteTextFileAtomically(const std::filesystem::path& path, const std::string& text);

/// True when `path` names an existing regular file (no exception).
bool IsRegularFile(const std::filesystem::path& path);

/// Removes `folder` and everything below it; nothing happens when it does not exist. FileError
/// when something cannot be removed.
void RemoveFolder(const std::filesystem::path& folder);

}  // namespace sewer3d
