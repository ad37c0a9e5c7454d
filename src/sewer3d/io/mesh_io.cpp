#include "sewer3d/io/mesh_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <iterator>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;

// glTF 2.0 constants (Khronos glTF 2.0 specification, §3.6 and §4.4).
constexpr std::uint32_t kGlbMagic = 0x46546C67;    // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;   // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;    // "BIN\0"
constexpr int kFloat = 5126, kUnsignedInt = 5125;  // accessor component types
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

static_assert(std::endian::native == std::endian::little,
              "the GLB writer copies little-endian floats and integers as they are in memory");

void CheckMesh(const TriangleMesh& mesh) {
  SEWER3D_CHECK(!mesh.triangles.empty(), "a mesh file needs at least one triangle");
  SEWER3D_CHECK(mesh.normals.size() == mesh.VertexCount() && mesh.uvs.size() == mesh.VertexCount());
}

// Appends raw bytes to the binary chunk and returns the bufferView describing them.
template <typename T>
json AppendView(std::string& bin, const T* data, std::size_t count, int target) {
  const std::size_t offset = bin.size();
  bin.append(reinterpret_cast<const char*>(data), count * sizeof(T));
  bin.resize((bin.size() + 3) & ~std::size_t{3}, '\0');  // every view starts 4-byte aligned
  json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", count * sizeof(T)}};
  if (target != 0) view["target"] = target;
  return view;
}

json PositionAccessor(const TriangleMesh& mesh) {
  Eigen::Vector3f lo = mesh.positions.front(), hi = lo;
  for (const auto& p : mesh.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return {{"bufferView", 0},
          {"componentType", kFloat},
          {"count", mesh.VertexCount()},
          {"type", "VEC3"},
          {"min", json::array({lo.x(), lo.y(), lo.z()})},
          {"max", json::array({hi.x(), hi.y(), hi.z()})}};
}

// The GLB container: 12-byte header, the JSON chunk padded with spaces, the BIN chunk padded
// with zeros (glTF 2.0 §4.4); chunk lengths are multiples of 4.
std::string GlbBytes(std::string json_text, std::string bin) {
  json_text.resize((json_text.size() + 3) & ~std::size_t{3}, ' ');
  bin.resize((bin.size() + 3) & ~std::size_t{3}, '\0');
  const auto total = static_cast<std::uint32_t>(12 + 8 + json_text.size() + 8 + bin.size());
  std::string out;
  const auto put32 = [&out](std::uint32_t v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  };
  put32(kGlbMagic);
  put32(2);
  put32(total);
  put32(static_cast<std::uint32_t>(json_text.size()));
  put32(kChunkJson);
  out += json_text;
  put32(static_cast<std::uint32_t>(bin.size()));
  put32(kChunkBin);
  out += bin;
  return out;
}

}  // namespace

void WriteObj(const std::filesystem::path& path_obj, const TriangleMesh& mesh,
              const std::string& texture_file_name) {
  CheckMesh(mesh);
  std::filesystem::path path_mtl = path_obj;
  path_mtl.replace_extension(".mtl");
  WriteTextFileAtomically(path_mtl, fmt::format("# sewer3d pipe model\nnewmtl pipe_wall\n"
                                                "Ka 1 1 1\nKd 1 1 1\nKs 0 0 0\nd 1\nillum 1\n"
                                                "map_Kd {}\n",
                                                texture_file_name));
  fmt::memory_buffer text;
  auto out = std::back_inserter(text);
  fmt::format_to(out, "# sewer3d pipe model: mm, model frame (z along the pipe, y down)\n");
  fmt::format_to(out, "mtllib {}\nusemtl pipe_wall\n", path_mtl.filename().string());
  for (const auto& p : mesh.positions) fmt::format_to(out, "v {} {} {}\n", p.x(), p.y(), p.z());
  for (const auto& t : mesh.uvs) fmt::format_to(out, "vt {} {}\n", t.x(), 1.0f - t.y());
  for (const auto& n : mesh.normals) fmt::format_to(out, "vn {} {} {}\n", n.x(), n.y(), n.z());
  for (const auto& f : mesh.triangles) {
    // OBJ indices are 1-based; position, uv and normal share the index.
    fmt::format_to(out, "f {0}/{0}/{0} {1}/{1}/{1} {2}/{2}/{2}\n", f[0] + 1, f[1] + 1, f[2] + 1);
  }
  WriteTextFileAtomically(path_obj, fmt::to_string(text));
}

void WriteGlb(const std::filesystem::path& path, const TriangleMesh& mesh,
              const std::vector<std::uint8_t>& texture_png) {
  CheckMesh(mesh);
  SEWER3D_CHECK(!texture_png.empty(), "the GLB's texture is empty");
  const std::size_t n = mesh.VertexCount();
  std::string bin;
  json views = json::array();
  views.push_back(AppendView(bin, mesh.positions.data(), n, kArrayBuffer));
  views.push_back(AppendView(bin, mesh.normals.data(), n, kArrayBuffer));
  views.push_back(AppendView(bin, mesh.uvs.data(), n, kArrayBuffer));
  views.push_back(
      AppendView(bin, mesh.triangles.data(), mesh.triangles.size(), kElementArrayBuffer));
  views.push_back(AppendView(bin, texture_png.data(), texture_png.size(), 0));
  static_assert(sizeof(Eigen::Vector3f) == 12 && sizeof(Eigen::Vector2f) == 8 &&
                sizeof(std::array<std::uint32_t, 3>) == 12);
  const json accessors =
      json::array({PositionAccessor(mesh),
                   {{"bufferView", 1}, {"componentType", kFloat}, {"count", n}, {"type", "VEC3"}},
                   {{"bufferView", 2}, {"componentType", kFloat}, {"count", n}, {"type", "VEC2"}},
                   {{"bufferView", 3},
                    {"componentType", kUnsignedInt},
                    {"count", 3 * mesh.triangles.size()},
                    {"type", "SCALAR"}}});
  const json primitive = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
                          {"indices", 3},
                          {"material", 0},
                          {"mode", 4}};
  const json material = {
      {"name", "pipe wall"},
      {"pbrMetallicRoughness",
       {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}},
      {"doubleSided", true}};
  // mm → m, and y down → y up by half a turn about x (quaternion x, y, z, w).
  const json node = {{"name", "pipe"},
                     {"mesh", 0},
                     {"rotation", json::array({1.0, 0.0, 0.0, 0.0})},
                     {"scale", json::array({0.001, 0.001, 0.001})}};
  json gltf;
  gltf["asset"] = {{"version", "2.0"}, {"generator", "sewer3d"}};
  gltf["scene"] = 0;
  gltf["scenes"] = json::array({json{{"nodes", json::array({0})}}});
  gltf["nodes"] = json::array({node});
  gltf["meshes"] = json::array({json{{"name", "pipe"}, {"primitives", json::array({primitive})}}});
  gltf["materials"] = json::array({material});
  gltf["samplers"] = json::array(
      {json{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}});
  gltf["textures"] = json::array({json{{"sampler", 0}, {"source", 0}}});
  gltf["images"] = json::array({json{{"bufferView", 4}, {"mimeType", "image/png"}}});
  gltf["buffers"] = json::array({json{{"byteLength", bin.size()}}});
  gltf["bufferViews"] = views;
  gltf["accessors"] = accessors;
  // The GLB is written by hand (a few lines of container format) rather than with a glTF
  // library, so the project needs no further package.
  WriteTextFileAtomically(path, GlbBytes(gltf.dump(), std::move(bin)));
}

void WriteGlb(const std::filesystem::path& path, const TriangleMesh& mesh,
              const cv::Mat3b& texture_bgr, int max_texture_side_px) {
  SEWER3D_CHECK(!texture_bgr.empty() && max_texture_side_px > 0);
  cv::Mat3b texture = texture_bgr;
  const int side = std::max(texture.rows, texture.cols);
  if (side > max_texture_side_px) {
    const double f = static_cast<double>(max_texture_side_px) / side;
    const cv::Size size(std::max(1, static_cast<int>(texture.cols * f)),
                        std::max(1, static_cast<int>(texture.rows * f)));
    cv::resize(texture_bgr, texture, size, 0.0, 0.0, cv::INTER_AREA);
  }
  std::vector<std::uint8_t> png;
  if (!cv::imencode(".png", texture, png)) throw FileError(path, "cannot encode the texture");
  WriteGlb(path, mesh, png);
}

}  // namespace sewer3d
