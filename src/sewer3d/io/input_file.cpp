#include "sewer3d/io/input_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <iterator>

#include "sewer3d/io/file_error.hpp"

namespace sewer3d {
namespace {

std::uint64_t BigEndian(const std::vector<std::uint8_t>& b, size_t at, int bytes) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | b[at + i];
  return v;
}

std::uint64_t Endian(const std::vector<std::uint8_t>& b, size_t at, int bytes, bool little) {
  if (!little) return BigEndian(b, at, bytes);
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | b[at + i];
  return v;
}

std::optional<ImageSize> PngSize(const std::vector<std::uint8_t>& b) {
  // Signature (8), IHDR length (4), "IHDR" (4), width (4), height (4).
  if (b.size() < 24 || b[12] != 'I' || b[13] != 'H' || b[14] != 'D' || b[15] != 'R')
    return std::nullopt;
  return ImageSize{BigEndian(b, 16, 4), BigEndian(b, 20, 4)};
}

/// The first IFD's ImageWidth (256) and ImageLength (257) tags.
std::optional<ImageSize> TiffSize(const std::vector<std::uint8_t>& b) {
  const bool little = b[0] == 'I';
  const std::uint64_t ifd = Endian(b, 4, 4, little);
  if (ifd + 2 > b.size()) return std::nullopt;
  const std::uint64_t entries = Endian(b, ifd, 2, little);
  ImageSize size;
  for (std::uint64_t e = 0; e < entries; ++e) {
    const std::uint64_t at = ifd + 2 + 12 * e;
    if (at + 12 > b.size()) return std::nullopt;
    const std::uint64_t tag = Endian(b, at, 2, little), type = Endian(b, at + 2, 2, little);
    const std::uint64_t value =
        type == 3 ? Endian(b, at + 8, 2, little) : Endian(b, at + 8, 4, little);
    if (tag == 256) size.width = value;
    if (tag == 257) size.height = value;
  }
  if (size.width == 0 || size.height == 0) return std::nullopt;
  return size;
}

/// The first start-of-frame marker (SOF0..SOF15 but DHT, JPG, DAC).
std::optional<ImageSize> JpegSize(const std::vector<std::uint8_t>& b) {
  size_t at = 2;
  while (at + 9 <= b.size() && b[at] == 0xFF) {
    const std::uint8_t marker = b[at + 1];
    const bool sof =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) return ImageSize{BigEndian(b, at + 7, 2), BigEndian(b, at + 5, 2)};
    at += 2 + BigEndian(b, at + 2, 2);
  }
  return std::nullopt;
}

}  // namespace

std::uintmax_t CheckInputFile(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory)
    throw FileError(path, "cannot be read: " + ec.message());  // a link loop, no permission
  if (ec || !std::filesystem::exists(status)) throw FileError(path, "no such file");
  if (std::filesystem::is_directory(status)) throw FileError(path, "is a folder, not a file");
  if (!std::filesystem::is_regular_file(status))
    throw FileError(path, "not a regular file (a FIFO, socket or device)");
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec) throw FileError(path, "cannot read its size: " + ec.message());
  if (bytes > max_bytes)
    throw FileError(path, fmt::format("{} bytes, more than the {} allowed", bytes, max_bytes));
  return bytes;
}

std::vector<std::uint8_t> ReadFileBytes(const std::filesystem::path& path,
                                        std::uintmax_t max_bytes) {
  const std::uintmax_t size = CheckInputFile(path, max_bytes);
  std::ifstream file(path, std::ios::binary);
  if (!file) throw FileError(path, "cannot open file");
  std::vector<std::uint8_t> bytes(size);
  file.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(file.gcount()) != size) throw FileError(path, "cannot read file");
  return bytes;
}

std::string ImageFormat(const std::vector<std::uint8_t>& b) {
  if (b.size() >= 8 && b[0] == 0x89 && b[1] == 'P' && b[2] == 'N' && b[3] == 'G') return "PNG";
  const bool tiff = b.size() >= 8 && ((b[0] == 'I' && b[1] == 'I' && b[2] == 42 && b[3] == 0) ||
                                      (b[0] == 'M' && b[1] == 'M' && b[2] == 0 && b[3] == 42));
  if (tiff) return "TIFF";
  if (b.size() >= 4 && b[0] == 0xFF && b[1] == 0xD8) return "JPEG";
  return "";
}

std::optional<ImageSize> ImageHeaderSize(const std::vector<std::uint8_t>& b) {
  const std::string format = ImageFormat(b);
  if (format == "PNG") return PngSize(b);
  if (format == "TIFF") return TiffSize(b);
  if (format == "JPEG") return JpegSize(b);
  return std::nullopt;
}

void CheckNotAnInput(const std::filesystem::path& output, const std::filesystem::path& input,
                     const std::string& option) {
  std::error_code ec;
  const bool same = std::filesystem::equivalent(output, input, ec) && !ec;
  if (same || output.lexically_normal() == input.lexically_normal()) {
    throw FileError(output, fmt::format("is also the input {} ({}): it would be overwritten; "
                                        "choose another output",
                                        option, input.string()));
  }
}

}  // namespace sewer3d
