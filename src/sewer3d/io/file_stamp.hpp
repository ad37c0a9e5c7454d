#pragma once
/// \file
/// What a processed input file was, so that a resumed stage can tell a file replaced since
/// from the one it processed: size, modification time and a hash of the content. The time is
/// the cheap first test; a file copied with a new time but the same bytes still matches.

#include <cstdint>
#include <filesystem>

namespace sewer3d {

struct FileStamp {
  std::uintmax_t bytes = 0;
  std::int64_t mtime_ns = 0;  ///< modification time, since the Unix epoch
  std::uint64_t hash = 0;     ///< of the whole content (ContentHash)
};

/// A 64-bit hash of `size` bytes (not cryptographic: it tells replaced files apart, it does not
/// resist forgery).
std::uint64_t ContentHash(const std::uint8_t* data, std::size_t size);

/// The stamp of the regular file `path`, read whole (FileError when it cannot be).
FileStamp StampFile(const std::filesystem::path& path);

/// Whether `path` still holds what `recorded` stamped: same size and time, or when the time
/// differs, the same content. False when the file is gone or unreadable.
bool StillStamped(const FileStamp& recorded, const std::filesystem::path& path);

}  // namespace sewer3d
