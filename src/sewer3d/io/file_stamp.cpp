#include "sewer3d/io/file_stamp.hpp"

#include <chrono>
#include <cstring>
#include <system_error>
#include <vector>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/input_file.hpp"

namespace sewer3d {
namespace {

// Nanoseconds since the Unix epoch (libstdc++'s file clock counts from another epoch).
std::int64_t ModificationTimeNs(const std::filesystem::path& path, std::error_code& ec) {
  const auto time = std::chrono::file_clock::to_sys(std::filesystem::last_write_time(path, ec));
  return std::chrono::duration_cast<std::chrono::nanoseconds>(time.time_since_epoch()).count();
}

}  // namespace

std::uint64_t ContentHash(const std::uint8_t* data, std::size_t size) {
  // 8 bytes at a time, each word mixed in with a multiply and a rotation (an FNV-like
  // multiplicative hash over words), the length folded in last; then a splitmix finaliser.
  constexpr std::uint64_t kPrime = 0x100000001b3ULL;
  std::uint64_t h = 0xcbf29ce484222325ULL;
  std::size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    std::uint64_t word = 0;
    std::memcpy(&word, data + i, 8);
    h = ((h ^ word) * kPrime);
    h = (h << 29) | (h >> 35);
  }
  for (; i < size; ++i) h = (h ^ data[i]) * kPrime;
  h ^= size;
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

FileStamp StampFile(const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = ReadFileBytes(path);
  std::error_code ec;
  FileStamp stamp;
  stamp.bytes = bytes.size();
  stamp.mtime_ns = ModificationTimeNs(path, ec);
  if (ec) throw FileError(path, "cannot read its modification time: " + ec.message());
  stamp.hash = ContentHash(bytes.data(), bytes.size());
  return stamp;
}

bool StillStamped(const FileStamp& recorded, const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec || bytes != recorded.bytes) return false;
  const std::int64_t mtime_ns = ModificationTimeNs(path, ec);
  if (!ec && mtime_ns == recorded.mtime_ns) return true;
  try {
    return StampFile(path).hash == recorded.hash;
  } catch (const FileError&) {
    return false;
  }
}

}  // namespace sewer3d
