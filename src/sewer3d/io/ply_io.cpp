#include "sewer3d/io/ply_io.hpp"

#include <fmt/core.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/input_file.hpp"

namespace sewer3d {
namespace {

constexpr const char* kPlyComment = "comment sewer3d, mm, ";

}  // namespace

void WritePly(const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& points,
              const std::vector<std::array<std::uint8_t, 3>>& colours, const std::string& frame) {
  if (!colours.empty() && colours.size() != points.size()) {
    throw FileError(path, "colours and points differ in number");
  }
  WriteFileAtomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream file(temporary, std::ios::binary);
    if (!file) throw FileError(path, "cannot open for writing");
    file << "ply\nformat binary_little_endian 1.0\n"
         << kPlyComment << frame << "\n"
         << "element vertex " << points.size()
         << "\nproperty float x\nproperty float y\nproperty float z\n";
    if (!colours.empty()) file << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    file << "end_header\n";
    for (size_t i = 0; i < points.size(); ++i) {
      const float xyz[3] = {static_cast<float>(points[i].x()), static_cast<float>(points[i].y()),
                            static_cast<float>(points[i].z())};
      file.write(reinterpret_cast<const char*>(xyz), sizeof(xyz));
      if (!colours.empty()) file.write(reinterpret_cast<const char*>(colours[i].data()), 3);
    }
    if (!file.flush()) throw FileError(path, "write failed (disk full?)");
  });
}

namespace {

struct PlyProperty {
  std::string type, name;
  int bytes = 0;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  std::string format;
  std::string frame;  ///< from sewer3d's comment ("camera frame"); empty for other writers
  std::vector<PlyElement> elements;
};

int TypeBytes(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

PlyHeader ReadPlyHeader(std::istream& file, const std::filesystem::path& path) {
  std::string line;
  if (!std::getline(file, line) || line.rfind("ply", 0) != 0)
    throw FileError(path, "not a PLY file");
  PlyHeader header;
  while (std::getline(file, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream in(line);
    std::string word;
    in >> word;
    if (word == "end_header") {
      if (header.format.empty()) throw FileError(path, "PLY header has no format line");
      return header;
    }
    if (word == "format") {
      in >> header.format;
    } else if (word == "element") {
      PlyElement element;
      std::string count;
      if (!(in >> element.name >> count))
        throw FileError(path, "PLY element line without a name and count: " + line);
      // Digits only: stream extraction would wrap "-5" to 2^64 - 5.
      if (count.find_first_not_of("0123456789") != std::string::npos || count.size() > 19)
        throw FileError(path, "element " + element.name + ": count '" + count +
                                  "' is not a whole number below 10^19");
      element.count = std::strtoull(count.c_str(), nullptr, 10);
      for (const PlyElement& other : header.elements) {
        if (other.name == element.name)
          throw FileError(path, "PLY element '" + element.name + "' declared twice");
      }
      header.elements.push_back(element);
    } else if (word == "property") {
      if (header.elements.empty()) throw FileError(path, "PLY property before any element");
      PlyProperty property;
      in >> property.type >> property.name;
      if (property.type == "list") {
        if (header.elements.back().name == "vertex")
          throw FileError(path, "list property in vertex element");
      } else if ((property.bytes = TypeBytes(property.type)) == 0) {
        throw FileError(path, "unknown PLY property type '" + property.type + "'");
      }
      for (const PlyProperty& other : header.elements.back().properties) {
        if (other.name == property.name && property.type != "list")
          throw FileError(path, "PLY property '" + property.name + "' declared twice");
      }
      header.elements.back().properties.push_back(property);
    } else if (line.rfind(kPlyComment, 0) == 0) {
      header.frame = line.substr(std::string(kPlyComment).size());
    } else if (word != "comment" && word != "obj_info" && !word.empty()) {
      throw FileError(path, "unknown PLY header line: " + ShownBytes(line.substr(0, 60)));
    }
  }
  throw FileError(path, "PLY header has no end_header line");
}

/// One binary value of PLY type `type` (`bytes` long) as a double.
double DecodeBinary(const char* b, const std::string& type, int bytes, bool big_endian) {
  unsigned char raw[8];
  for (int i = 0; i < bytes; ++i)
    raw[i] = static_cast<unsigned char>(b[big_endian ? bytes - 1 - i : i]);
  const bool is_signed = type == "char" || type == "int8" || type == "short" || type == "int16" ||
                         type == "int" || type == "int32";
  if (type == "float" || type == "float32") {
    float f;
    std::memcpy(&f, raw, 4);
    return f;
  }
  if (type == "double" || type == "float64") {
    double d;
    std::memcpy(&d, raw, 8);
    return d;
  }
  std::uint64_t u = 0;
  for (int i = bytes - 1; i >= 0; --i) u = (u << 8) | raw[i];
  if (!is_signed) return static_cast<double>(u);
  const std::uint64_t sign = std::uint64_t{1} << (8 * bytes - 1);
  return static_cast<double>(static_cast<std::int64_t>(u ^ sign) - static_cast<std::int64_t>(sign));
}

void ThrowCount(const std::filesystem::path& path, std::uint64_t read, std::uint64_t declared) {
  throw FileError(
      path, "truncated: " + std::to_string(read) + " of " + std::to_string(declared) + " vertices");
}

// One ASCII vertex, n, from its line (blank lines skipped): as many numbers as the header
// declares properties. False at the end of the file.
bool ReadAsciiVertex(std::istream& file, const std::filesystem::path& path, std::uint64_t n,
                     std::vector<double>& values) {
  std::string line;
  do {
    if (!std::getline(file, line)) return false;
  } while (line.find_first_not_of(" \t\r") == std::string::npos);
  std::istringstream in(line);
  std::string token;
  size_t k = 0;
  for (; in >> token; ++k) {
    if (k == values.size()) {
      throw FileError(path, fmt::format("vertex {}: more values than the {} properties the "
                                        "header declares",
                                        n, values.size()));
    }
    char* end = nullptr;
    values[k] = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size()) {
      throw FileError(path, fmt::format("vertex {}: '{}' is not a number", n, token.substr(0, 20)));
    }
  }
  if (k < values.size()) {
    throw FileError(path, fmt::format("vertex {}: {} values, but the header declares {} "
                                      "properties",
                                      n, k, values.size()));
  }
  return true;
}

}  // namespace

std::vector<Eigen::Vector3d> ReadPlyPoints(const std::filesystem::path& path, std::string* frame) {
  const std::uintmax_t file_bytes =
      CheckInputFile(path, std::numeric_limits<std::uintmax_t>::max());
  std::ifstream file(path, std::ios::binary);
  if (!file) throw FileError(path, "cannot open file");
  const PlyHeader header = ReadPlyHeader(file, path);
  if (frame != nullptr) *frame = header.frame;
  const bool ascii = header.format == "ascii";
  const bool big = header.format == "binary_big_endian";
  if (!ascii && !big && header.format != "binary_little_endian")
    throw FileError(path, "unsupported PLY format '" + header.format + "'");
  if (header.elements.empty() || header.elements.front().name != "vertex")
    throw FileError(path, "vertex element must come first");
  const PlyElement& vertex = header.elements.front();
  int xyz[3] = {-1, -1, -1};
  size_t stride = 0;
  for (size_t i = 0; i < vertex.properties.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (vertex.properties[i].name == std::string(1, "xyz"[k])) xyz[k] = static_cast<int>(i);
    }
    stride += vertex.properties[i].bytes;
  }
  if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) throw FileError(path, "vertices lack x, y or z");
  // The count must fit in the body before anything is allocated for it (ASCII needs at least
  // two characters a value).
  const std::uintmax_t body = file_bytes - static_cast<std::uintmax_t>(file.tellg());
  const std::uintmax_t least = ascii ? 2 * vertex.properties.size() : stride;
  if (vertex.count > body / least) ThrowCount(path, body / least, vertex.count);
  std::vector<Eigen::Vector3d> points(vertex.count);
  std::vector<double> values(vertex.properties.size());
  std::vector<char> record(stride);
  for (std::uint64_t n = 0; n < vertex.count; ++n) {
    if (ascii) {
      if (!ReadAsciiVertex(file, path, n, values)) ThrowCount(path, n, vertex.count);
    } else if (file.read(record.data(), static_cast<std::streamsize>(stride))) {
      size_t at = 0;
      for (size_t i = 0; i < values.size(); ++i) {
        const PlyProperty& p = vertex.properties[i];
        values[i] = DecodeBinary(record.data() + at, p.type, p.bytes, big);
        at += p.bytes;
      }
    }
    if (!file) ThrowCount(path, n, vertex.count);
    points[n] = {values[xyz[0]], values[xyz[1]], values[xyz[2]]};
    if (!points[n].allFinite())
      throw FileError(path, "vertex " + std::to_string(n) + ": a coordinate is not finite");
    // A thousand kilometres in millimetres: beyond it the cloud is in other units or corrupt,
    // and fits would lose every millimetre to rounding.
    if (points[n].cwiseAbs().maxCoeff() > 1e9) {
      throw FileError(path, fmt::format("vertex {}: coordinate {:g} is beyond ±1e9 mm", n,
                                        points[n].cwiseAbs().maxCoeff()));
    }
  }
  // With only vertices declared, anything after them means the count is wrong.
  if (header.elements.size() == 1) {
    if (ascii) file >> std::ws;
    if (file.peek() != std::char_traits<char>::eof())
      throw FileError(path, "the body holds more than the " + std::to_string(vertex.count) +
                                " vertices the header declares");
  }
  return points;
}

}  // namespace sewer3d
