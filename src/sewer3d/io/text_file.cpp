#include "sewer3d/io/text_file.hpp"

#include <fstream>
#include <vector>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/input_file.hpp"

namespace sewer3d {

std::string ReadTextFile(const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = ReadFileBytes(path);
  return {bytes.begin(), bytes.end()};
}

void WriteTextFile(const std::filesystem::path& path, std::string_view text) {
  WriteFileAtomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream file(temporary, std::ios::binary);
    if (!file) throw FileError(path, "cannot open for writing");
    file.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!file.flush()) throw FileError(path, "write failed (disk full?)");
  });
}

std::string EscapeMarkup(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace sewer3d
