#include "sewer3d/io/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <system_error>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {

// Unique within the process (threads write different files at once) and across processes
// (the pid): two writers never share a temporary.
std::filesystem::path TemporaryPathFor(const std::filesystem::path& path) {
  static std::atomic<unsigned long> next{0};
  std::string name = ".";
  name += path.filename().string();
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(next++);
  name += path.extension().string();
  return path.parent_path() / name;
}

void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path&)>& write) {
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  if (ec) throw FileError(path.parent_path(), "cannot create folder: " + ec.message());
  const std::filesystem::path temporary = TemporaryPathFor(path);
  try {
    write(temporary);
  } catch (...) {
    std::filesystem::remove(temporary, ec);
    throw;
  }
  std::filesystem::rename(temporary, path, ec);  // POSIX rename: atomic within one file system
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw FileError(path, "cannot rename the finished temporary file over it: " + ec.message());
  }
}

void WriteTextFileAtomically(const std::filesystem::path& path, const std::string& text) {
  WriteFileAtomically(
      path, [&](const std::filesystem::path& temporary) { WriteTextFile(temporary, text); });
}

bool IsRegularFile(const std::filesystem::path& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

void RemoveFolder(const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::remove_all(folder, ec);
  if (ec) throw FileError(folder, "cannot remove folder: " + ec.message());
}

}  // namespace sewer3d
