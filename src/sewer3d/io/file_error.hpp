#pragma once
/// \file
/// The exception io/ throws for bad files: its message is one line, "PATH: what is wrong".

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>

namespace sewer3d {

class FileError : public std::runtime_error {
 public:
  FileError(const std::filesystem::path& path, const std::string& problem)
      : std::runtime_error(path.string() + ": " + problem), path_(path) {}
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
