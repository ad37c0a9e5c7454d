#pragma once
/// \file
/// Checks on a file before it is opened or decoded: a regular file (never a FIFO, device or
/// folder, which would block or stream forever), of a bounded size, and for images a pixel
/// count read from the header before any decoding allocates it. Errors are FileError.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sewer3d {

/// Largest input file read whole (text, JSON, CSV, image): 2 GiB.
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{2} << 30;

/// Throws FileError "no such file", "is a folder, not a file", "not a regular file (a FIFO,
/// socket or device)" or "N bytes, more than the M allowed" unless `path` is a regular file of
/// at most max_bytes; returns its size. Call it before opening the file.
std::uintmax_t CheckInputFile(const std::filesystem::path& path,
                              std::uintmax_t max_bytes = kMaxInputFileBytes);

/// CheckInputFile, then the whole file's bytes.
std::vector<std::uint8_t> ReadFileBytes(const std::filesystem::path& path,
                                        std::uintmax_t max_bytes = kMaxInputFileBytes);

/// FileError naming `output` when it is the file `input` (the same path, or a link to it): the
/// result would overwrite what it is made from. `option` names the input ("--image").
void CheckNotAnInput(const std::filesystem::path& output, const std::filesystem::path& input,
                     const std::string& option);

struct ImageSize {
  std::uint64_t width = 0, height = 0;
};

/// "PNG", "TIFF" or "JPEG" by the file's signature, or "".
std::string ImageFormat(const std::vector<std::uint8_t>& bytes);

/// Width and height as a PNG, TIFF or JPEG header declares them (nullopt for other formats
/// or a header too short to tell).
std::optional<ImageSize> ImageHeaderSize(const std::vector<std::uint8_t>& bytes);

}  // namespace sewer3d
