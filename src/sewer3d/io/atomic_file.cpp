#include "sewer3d/io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"

namespace sewer3d {

namespace {

std::mutex new_outputs_mutex;
bool new_outputs_active = false;
std::vector<std::filesystem::path> new_outputs;

void NoteNewOutput(const std::filesystem::path& path) {
  const std::lock_guard<std::mutex> lock(new_outputs_mutex);
  if (new_outputs_active) new_outputs.push_back(path);
}

}  // namespace

NewOutputs::NewOutputs() {
  const std::lock_guard<std::mutex> lock(new_outputs_mutex);
  if (new_outputs_active) throw std::logic_error("NewOutputs: one at a time");
  new_outputs_active = true;
  new_outputs.clear();
}

NewOutputs::~NewOutputs() {
  const std::lock_guard<std::mutex> lock(new_outputs_mutex);
  if (!keep_) {
    std::error_code ignored;  // best effort: the command is failing already
    // Newest first, so that a folder it created is empty when its turn comes (a folder that
    // holds something else stays).
    for (auto p = new_outputs.rbegin(); p != new_outputs.rend(); ++p)
      std::filesystem::remove(*p, ignored);
  }
  new_outputs.clear();
  new_outputs_active = false;
}

void CreateOutputFolder(const std::filesystem::path& folder) {
  std::error_code ec;
  std::vector<std::filesystem::path> missing;
  for (std::filesystem::path up = folder; !up.empty() && !std::filesystem::exists(up, ec);
       up = up.parent_path()) {
    missing.push_back(up);
    if (up == up.parent_path()) break;
  }
  std::filesystem::create_directories(folder, ec);
  if (ec) throw FileError(folder, "cannot create folder: " + ec.message());
  for (auto f = missing.rbegin(); f != missing.rend(); ++f) NoteNewOutput(*f);
}

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

namespace {

// Linux file systems hold names of up to 255 bytes; the temporary adds its suffix to the name.
void CheckNameLength(const std::filesystem::path& path) {
  constexpr std::size_t kNameMax = 255;
  const std::size_t name = path.filename().string().size();
  const std::size_t temporary = TemporaryPathFor(path).filename().string().size();
  if (temporary <= kNameMax) return;
  const std::string limit = "the file system's limit of " + std::to_string(kNameMax) + " bytes";
  throw FileError(path,
                  "the file name is " + std::to_string(name) + " bytes long" +
                      (name > kNameMax ? ", over " + limit
                                       : "; with the " + std::to_string(temporary - name) +
                                             " bytes its temporary name adds, over " + limit));
}

}  // namespace

void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path&)>& write) {
  std::error_code ec;
  if (path.empty()) throw FileError(path, "an empty file name");
  CheckNameLength(path);
  // Renaming over a FIFO or a device (/dev/null as root) would replace it with a plain file.
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status)) throw FileError(path, "is a folder, not a file");
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw FileError(path, "not a regular file (a FIFO, socket or device); not replaced");
  ec.clear();
  if (path.has_parent_path()) CreateOutputFolder(path.parent_path());
  const std::filesystem::path temporary = TemporaryPathFor(path);
  try {
    write(temporary);
  } catch (...) {
    std::filesystem::remove(temporary, ec);
    throw;
  }
  const bool existed = std::filesystem::exists(status);
  std::filesystem::rename(temporary, path, ec);  // POSIX rename: atomic within one file system
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw FileError(path, "cannot rename the finished temporary file over it: " + ec.message());
  }
  if (!existed) NoteNewOutput(path);
}

void WriteTextFileAtomically(const std::filesystem::path& path, const std::string& text) {
  WriteTextFile(path, text);
}

void CheckOutputFile(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(path, ec);
  if (fs::is_directory(path, ec)) throw FileError(path, "is a folder, not a file");
  if (!path.has_filename()) throw FileError(path, "names a folder (ends with /), not a file");
  CheckNameLength(path);
  if (fs::exists(status) && !fs::is_regular_file(status) && !fs::is_symlink(status))
    throw FileError(path, "not a regular file (a FIFO, socket or device); not replaced");
  fs::path above = fs::absolute(path, ec).parent_path();
  while (!fs::exists(above, ec) && above.has_parent_path() && above != above.parent_path())
    above = above.parent_path();
  if (!fs::is_directory(above, ec))
    throw FileError(path, "cannot be written: " + above.string() + " is not a folder");
  if (::access(above.c_str(), W_OK) != 0)
    throw FileError(path, "cannot be written: " + above.string() + " is not writable");
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

int RemoveStaleTemporaries(const std::filesystem::path& folder) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) return 0;
  std::vector<std::filesystem::path> stale;
  for (auto it = std::filesystem::recursive_directory_iterator(folder, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() > 1 && name[0] == '.' && name.find(".tmp-") != std::string::npos) {
      stale.push_back(it->path());
      if (it->is_directory()) it.disable_recursion_pending();
    }
  }
  if (ec) throw FileError(folder, "cannot list folder: " + ec.message());
  for (const std::filesystem::path& p : stale) {
    std::filesystem::remove_all(p, ec);
    if (ec) throw FileError(p, "cannot remove stale temporary: " + ec.message());
  }
  return static_cast<int>(stale.size());
}

FolderLock::FolderLock(const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw FileError(folder, "cannot create folder: " + ec.message());
  const std::filesystem::path file = folder / ".lock";
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw FileError(file, "cannot open the lock file");
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd_);
    fd_ = -1;
    throw FileError(folder, "another sewer3d process is writing this workspace; wait for it");
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

FolderLock::FolderLock(FolderLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }

FolderLock& FolderLock::operator=(FolderLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

}  // namespace sewer3d
