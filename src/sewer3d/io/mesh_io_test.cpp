// Mesh files read back: the GLB's container (magic, version, lengths, chunk types and
// padding), its JSON (accessor counts, POSITION min/max, buffer length) and the binary data
// (positions, indices, the embedded PNG) match the mesh; the OBJ has one v/vt/vn per vertex and
// one f per triangle, with v flipped and the material naming the texture.

#include "sewer3d/io/mesh_io.hpp"

#include <gtest/gtest.h>
#include <tiny_obj_loader.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "sewer3d/io/text_file.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::uint32_t U32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, sizeof v);
  return v;
}

TriangleMesh SmallCylinder() {
  Centreline line;
  line.points = {{0.0, 0.0, 0.0}, {0.0, 0.0, 100.0}};
  line.crowns = {-Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitY()};
  line.step_mm = 100.0;
  const MapGrid grid{.resolution_mm = 1.0, .station0_mm = 0.0, .rows = 50, .cols = 942};
  return BuildBaseCylinder(line, grid, {.segments = 32, .ring_step_mm = 10.0});
}

class MeshIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sewer3d_mesh_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    mesh_ = SmallCylinder();
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  TriangleMesh mesh_;
};

TEST_F(MeshIoTest, GlbReadsBackAsWritten) {
  cv::Mat3b texture(50, 942, cv::Vec3b(40, 80, 120));
  WriteGlb(dir_ / "mesh.glb", mesh_, texture);
  const std::string bytes = ReadTextFile(dir_ / "mesh.glb");
  ASSERT_GE(bytes.size(), 28u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(U32(bytes, 4), 2u);
  EXPECT_EQ(U32(bytes, 8), bytes.size());
  const std::uint32_t json_length = U32(bytes, 12);
  EXPECT_EQ(bytes.substr(16, 4), "JSON");
  EXPECT_EQ(json_length % 4, 0u);
  const json gltf = json::parse(bytes.substr(20, json_length));  // trailing spaces are JSON
  const std::size_t bin_at = 20 + json_length;
  const std::uint32_t bin_length = U32(bytes, bin_at);
  EXPECT_EQ(bytes.substr(bin_at + 4, 4), std::string("BIN\0", 4));
  EXPECT_EQ(bin_length % 4, 0u);
  EXPECT_EQ(bin_at + 8 + bin_length, bytes.size());
  const std::string bin = bytes.substr(bin_at + 8);

  EXPECT_EQ(gltf["asset"]["version"], "2.0");
  const std::size_t buffer_length = gltf["buffers"][0]["byteLength"];
  EXPECT_LE(buffer_length, bin_length);
  EXPECT_GT(buffer_length + 4, bin_length);
  const json& attributes = gltf["meshes"][0]["primitives"][0]["attributes"];
  const json& accessors = gltf["accessors"];
  const std::size_t n = mesh_.VertexCount();
  EXPECT_EQ(accessors[attributes["POSITION"].get<int>()]["count"], n);
  EXPECT_EQ(accessors[attributes["NORMAL"].get<int>()]["count"], n);
  EXPECT_EQ(accessors[attributes["TEXCOORD_0"].get<int>()]["count"], n);
  const json& indices = accessors[gltf["meshes"][0]["primitives"][0]["indices"].get<int>()];
  EXPECT_EQ(indices["count"], 3 * mesh_.triangles.size());
  EXPECT_EQ(indices["componentType"], 5125);
  // Every view lies inside the buffer, 4-byte aligned.
  for (const json& view : gltf["bufferViews"]) {
    const std::size_t offset = view["byteOffset"], length = view["byteLength"];
    EXPECT_EQ(offset % 4, 0u);
    EXPECT_LE(offset + length, buffer_length);
  }
  // Positions and indices as the mesh holds them; min/max bound them exactly.
  const json& position = accessors[attributes["POSITION"].get<int>()];
  const std::size_t at = gltf["bufferViews"][position["bufferView"].get<int>()]["byteOffset"];
  for (std::size_t k = 0; k < n; ++k) {
    Eigen::Vector3f p;
    std::memcpy(p.data(), bin.data() + at + 12 * k, 12);
    ASSERT_EQ(p, mesh_.positions[k]);
    for (int c = 0; c < 3; ++c) {
      ASSERT_GE(p[c], position["min"][c].get<float>());
      ASSERT_LE(p[c], position["max"][c].get<float>());
    }
  }
  EXPECT_NEAR(position["max"][2].get<float>(), 50.0f, 1e-4);  // the pipe's 50 mm of stations
  const json& image_view = gltf["bufferViews"][gltf["images"][0]["bufferView"].get<int>()];
  const std::string png = bin.substr(image_view["byteOffset"], image_view["byteLength"]);
  const cv::Mat decoded =
      cv::imdecode(std::vector<uchar>(png.begin(), png.end()), cv::IMREAD_COLOR);
  ASSERT_EQ(decoded.size(), texture.size());
  EXPECT_EQ(decoded.at<cv::Vec3b>(10, 10), cv::Vec3b(40, 80, 120));
  EXPECT_EQ(gltf["images"][0]["mimeType"], "image/png");
  EXPECT_EQ(gltf["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"], 0);
}

// The Khronos glTF-Validator (tests/gltf_validate.js) finds no error: what a glTF viewer checks
// before it loads the file. CTest sets the variables when the validator was fetched.
TEST_F(MeshIoTest, GlbPassesTheKhronosValidator) {
  const char* node = std::getenv("SEWER3D_NODE");
  const char* script = std::getenv("SEWER3D_GLTF_VALIDATE");
  if (node == nullptr || script == nullptr) GTEST_SKIP() << "no glTF validator (npm, node)";
  WriteGlb(dir_ / "mesh.glb", mesh_, cv::Mat3b(50, 942, cv::Vec3b(40, 80, 120)));
  const std::string command = std::string("'") + node + "' '" + script + "' '" +
                              (dir_ / "mesh.glb").string() + "' > '" +
                              (dir_ / "validation.txt").string() + "' 2>&1";
  const int status = std::system(command.c_str());
  const std::string said = ReadTextFile(dir_ / "validation.txt");
  EXPECT_EQ(status, 0) << said;
  EXPECT_NE(said.find(" 0 errors"), std::string::npos) << said;
}

TEST_F(MeshIoTest, GlbShrinksAnOversizedTexture) {
  WriteGlb(dir_ / "mesh.glb", mesh_, cv::Mat3b(100, 1000, cv::Vec3b(1, 2, 3)), 250);
  const std::string bytes = ReadTextFile(dir_ / "mesh.glb");
  const json gltf = json::parse(bytes.substr(20, U32(bytes, 12)));
  const json& view = gltf["bufferViews"][gltf["images"][0]["bufferView"].get<int>()];
  const std::size_t bin_at = 20 + U32(bytes, 12) + 8;
  const std::string png = bytes.substr(bin_at + view["byteOffset"].get<std::size_t>(),
                                       view["byteLength"].get<std::size_t>());
  const cv::Mat decoded =
      cv::imdecode(std::vector<uchar>(png.begin(), png.end()), cv::IMREAD_COLOR);
  EXPECT_EQ(decoded.cols, 250);
  EXPECT_EQ(decoded.rows, 25);
}

TEST_F(MeshIoTest, ObjHasOneLinePerVertexAndTriangle) {
  WriteObj(dir_ / "mesh.obj", mesh_, "texture.png");
  std::istringstream obj(ReadTextFile(dir_ / "mesh.obj"));
  std::size_t v = 0, vt = 0, vn = 0, f = 0;
  std::string line, mtllib;
  float first_vt_v = -1.0f;
  while (std::getline(obj, line)) {
    std::istringstream in(line);
    std::string tag;
    in >> tag;
    if (tag == "v") ++v;
    if (tag == "vn") ++vn;
    if (tag == "f") ++f;
    if (tag == "mtllib") in >> mtllib;
    if (tag == "vt" && vt++ == 0) {
      float u = 0.0f;
      in >> u >> first_vt_v;
    }
  }
  EXPECT_EQ(v, mesh_.VertexCount());
  EXPECT_EQ(vt, mesh_.VertexCount());
  EXPECT_EQ(vn, mesh_.VertexCount());
  EXPECT_EQ(f, mesh_.triangles.size());
  EXPECT_EQ(first_vt_v, 1.0f);  // row 0 is the top of the image: OBJ's v = 1
  EXPECT_EQ(mtllib, "mesh.mtl");
  EXPECT_NE(ReadTextFile(dir_ / "mesh.mtl").find("map_Kd texture.png\n"), std::string::npos);
}

TEST_F(MeshIoTest, ObjOpensWithItsTextureInAMeshLibrary) {
  WriteObj(dir_ / "mesh.obj", mesh_, "texture.png");
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  tinyobj::ObjReader reader;
  ASSERT_TRUE(reader.ParseFromFile((dir_ / "mesh.obj").string(), config)) << reader.Error();
  EXPECT_TRUE(reader.Warning().empty()) << reader.Warning();
  ASSERT_EQ(reader.GetMaterials().size(), 1u);
  EXPECT_EQ(reader.GetMaterials()[0].diffuse_texname, "texture.png");
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  ASSERT_EQ(attrib.vertices.size(), 3 * mesh_.VertexCount());
  ASSERT_EQ(attrib.texcoords.size(), 2 * mesh_.VertexCount());
  ASSERT_EQ(attrib.normals.size(), 3 * mesh_.VertexCount());
  ASSERT_EQ(reader.GetShapes().size(), 1u);
  const tinyobj::mesh_t& read = reader.GetShapes()[0].mesh;
  ASSERT_EQ(read.num_face_vertices.size(), mesh_.triangles.size());
  for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
    ASSERT_EQ(read.num_face_vertices[t], 3);
    ASSERT_EQ(read.material_ids[t], 0);
    for (int c = 0; c < 3; ++c) {
      const tinyobj::index_t& corner = read.indices[3 * t + c];
      const std::uint32_t v = mesh_.triangles[t][c];
      ASSERT_EQ(corner.vertex_index, static_cast<int>(v));
      ASSERT_EQ(corner.texcoord_index, static_cast<int>(v));
    }
  }
  // Positions to float precision; the texture's v flipped (OBJ's origin is the bottom row).
  for (std::size_t i = 0; i < mesh_.VertexCount(); ++i) {
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(attrib.vertices[3 * i + k], mesh_.positions[i][k], 1e-4f) << i;
    ASSERT_NEAR(attrib.texcoords[2 * i], mesh_.uvs[i].x(), 1e-6f);
    ASSERT_NEAR(attrib.texcoords[2 * i + 1], 1.0f - mesh_.uvs[i].y(), 1e-6f);
  }
}

}  // namespace
}  // namespace sewer3d
