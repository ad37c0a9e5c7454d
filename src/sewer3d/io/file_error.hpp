#pragma once
/// \file
/// The exception io/ throws for bad files: its message is one line, "PATH: what is wrong".

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>

namespace sewer3d {

/// `path` as a message shows it: control characters (a newline in a file name) written as
/// C escapes (\n, \t, \x01), so that the one-line message names the real file.
inline std::string ShownPath(const std::filesystem::path& path) {
  static const char* const kHex = "0123456789abcdef";
  std::string shown;
  for (const char c : path.string()) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7f) {
      shown += c;
    } else if (c == '\n') {
      shown += "\\n";
    } else if (c == '\t') {
      shown += "\\t";
    } else {
      shown += std::string("\\x") + kHex[u >> 4] + kHex[u & 15];
    }
  }
  return shown;
}

/// Bytes of a file quoted in a message (a header line that may run into binary data): printable
/// ASCII as it is, every other byte as \xNN, so the message stays one line of plain text.
inline std::string ShownBytes(const std::string& bytes) {
  static const char* const kHex = "0123456789abcdef";
  std::string shown;
  for (const char c : bytes) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      shown += c;
    } else {
      shown += std::string("\\x") + kHex[u >> 4] + kHex[u & 15];
    }
  }
  return shown;
}

class FileError : public std::runtime_error {
 public:
  FileError(const std::filesystem::path& path, const std::string& problem)
      : std::runtime_error(ShownPath(path) + ": " + problem), path_(path) {}
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Runs `check`, the validation of what was read from `path` (a Check() that throws
/// std::invalid_argument "field: problem", see core/check.hpp), and turns its failure into the
/// FileError "PATH: field: problem". Internal errors pass through.
template <typename CheckFn>
void ValidateFileContents(const std::filesystem::path& path, CheckFn&& check) {
  try {
    std::forward<CheckFn>(check)();
  } catch (const std::invalid_argument& e) {
    throw FileError(path, e.what());
  }
}

}  // namespace sewer3d
