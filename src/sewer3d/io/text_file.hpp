#pragma once
/// \file
/// Whole text files in and out, with FileErrors naming the file.

#include <filesystem>
#include <string>
#include <string_view>

namespace sewer3d {

/// The file's bytes; FileError when it is missing, not a regular file or over 2 GiB
/// (CheckInputFile).
std::string ReadTextFile(const std::filesystem::path& path);
/// Writes the text atomically (temporary + rename, atomic_file.hpp), creating the file's
/// folder; FileError on failure, and then `path` is left as it was.
void WriteTextFile(const std::filesystem::path& path, std::string_view text);

/// `text` as XML / HTML character data or attribute value: & < > " ' as entities.
std::string EscapeMarkup(std::string_view text);

}  // namespace sewer3d
