#include "sewer3d/io/ply_io.hpp"

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "sewer3d/io/file_error.hpp"

namespace sewer3d {

void WritePly(const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& points,
              const std::vector<std::array<std::uint8_t, 3>>& colours) {
  if (!colours.empty() && colours.size() != points.size()) {
    throw FileError(path, "colours and points differ in number");
  }
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  std::ofstream file(path, std::ios::binary);
  if (!file) throw FileError(path, "cannot open for writing");
  file << "ply\nformat binary_little_endian 1.0\ncomment sewer3d, mm, camera frame\n"
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
  if (!file.flush()) throw FileError(path, "write failed");
}

std::vector<Eigen::Vector3d> ReadPlyPoints(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw FileError(path, "cannot open file");
  std::string line, format;
  size_t count = 0;
  bool in_vertex = false;
  std::vector<std::pair<std::string, std::string>> properties;  // (type, name) of vertices
  std::getline(file, line);
  if (line.rfind("ply", 0) != 0) throw FileError(path, "not a PLY file");
  while (std::getline(file, line)) {
    std::istringstream in(line);
    std::string word;
    in >> word;
    if (word == "format")
      in >> format;
    else if (word == "element") {
      std::string name;
      in >> name >> count;
      in_vertex = name == "vertex";
      if (!in_vertex && properties.empty()) throw FileError(path, "vertex element must come first");
    } else if (word == "property" && in_vertex) {
      std::string type, name;
      in >> type >> name;
      if (type == "list") throw FileError(path, "list property in vertex element");
      properties.emplace_back(type, name);
    } else if (word == "end_header")
      break;
  }
  auto size_of = [&](const std::string& t) -> int {
    if (t == "float" || t == "float32" || t == "int" || t == "uint" || t == "int32" ||
        t == "uint32")
      return 4;
    if (t == "double" || t == "float64") return 8;
    if (t == "uchar" || t == "char" || t == "uint8" || t == "int8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    throw FileError(path, "unknown property type " + t);
  };
  int xyz_index[3] = {-1, -1, -1};
  for (size_t i = 0; i < properties.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (properties[i].second == std::string(1, "xyz"[k])) xyz_index[k] = static_cast<int>(i);
    }
  }
  if (xyz_index[0] < 0 || xyz_index[1] < 0 || xyz_index[2] < 0)
    throw FileError(path, "vertices lack x, y or z");
  std::vector<Eigen::Vector3d> points(count);
  for (size_t n = 0; n < count; ++n) {
    double values[64] = {0};
    if (properties.size() > 64) throw FileError(path, "too many vertex properties");
    for (size_t i = 0; i < properties.size(); ++i) {
      const std::string& t = properties[i].first;
      if (format == "ascii") {
        file >> values[i];
      } else if (format == "binary_little_endian") {
        char buffer[8];
        const int size = size_of(t);
        file.read(buffer, size);
        if (t == "float" || t == "float32") {
          float f;
          std::memcpy(&f, buffer, 4);
          values[i] = f;
        } else if (t == "double" || t == "float64") {
          std::memcpy(&values[i], buffer, 8);
        } else if (size == 1)
          values[i] = static_cast<unsigned char>(buffer[0]);
      } else {
        throw FileError(path, "unsupported PLY format " + format);
      }
    }
    if (!file)
      throw FileError(
          path, "truncated: " + std::to_string(n) + " of " + std::to_string(count) + " vertices");
    points[n] = {values[xyz_index[0]], values[xyz_index[1]], values[xyz_index[2]]};
  }
  return points;
}

}  // namespace sewer3d
