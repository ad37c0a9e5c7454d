#pragma once
/// \file
/// The exception io/ throws for bad files: its message is one line, "PATH: what is wrong".

#include <filesystem>
#include <stdexcept>
#include <string>

namespace sewer3d {

class FileError : public std::runtime_error {
 public:
  FileError(const std::filesystem::path& path, const std::string& problem)
      : std::runtime_error(path.string() + ": " + problem), path_(path) {}
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace sewer3d
