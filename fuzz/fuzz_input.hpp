#pragma once
/// \file
/// Shared by the libFuzzer targets (docs/hardening.md): the input as a file for readers that
/// take a path, and the line between an expected refusal and a finding.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "sewer3d/io/file_error.hpp"

namespace sewer3d::fuzz {

/// Writes the input to one file per process (in /dev/shm when it exists, so each run costs no
/// disk I/O) and returns its path. The name ends in `extension`, as a user's file would; call
/// it with one extension per process.
inline std::filesystem::path InputFile(const std::uint8_t* data, std::size_t size,
                                       const std::string& extension) {
  const std::filesystem::path folder = std::filesystem::is_directory("/dev/shm")
                                           ? "/dev/shm"
                                           : std::filesystem::temp_directory_path();
  const std::filesystem::path path =
      folder / ("sewer3d_fuzz_" + std::to_string(getpid()) + extension);
  // Removed when the process exits normally (a crash leaves it, beside the finding).
  static const struct Remover {
    std::filesystem::path path;
    ~Remover() {
      std::error_code ec;
      std::filesystem::remove(path, ec);
    }
  } remover{path};
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!file.flush()) throw std::runtime_error("fuzz harness: cannot write " + path.string());
  return path;
}

/// Runs a reader on the input. A FileError (the io/ refusal) or an std::invalid_argument
/// (InvalidValue: a value the file supplies is not allowed) is the expected way to refuse bad
/// bytes. Anything else escapes: an InternalError, another exception (std::bad_alloc, a
/// library's own), a crash or a sanitizer report is a finding.
template <typename ReadFn>
void Refusing(ReadFn&& read) {
  try {
    read();
  } catch (const FileError&) {
  } catch (const std::invalid_argument&) {
  }
}

}  // namespace sewer3d::fuzz
