#pragma once
/// \file
/// Whole text files in and out, with FileErrors naming the file.

#include <filesystem>
#include <string>
#include <string_view>

namespace sewer3d {

/// The file's bytes; FileError "cannot open file" when it is missing or not a regular file.
std::string ReadTextFile(const std::filesystem::path& path);
/// Writes the text, creating the file's folder; FileError on failure.
void WriteTextFile(const std::filesystem::path& path, const std::string& text);

/// `text` as XML / HTML character data or attribute value: & < > " ' as entities.
std::string EscapeMarkup(std::string_view text);

}  // namespace sewer3d
