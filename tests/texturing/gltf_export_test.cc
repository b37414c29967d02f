// The exporters, checked by reading their output back and by the Khronos glTF-Validator.

#include "texturing/gltf_export.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "lib/geometry/mesh_io.h"
#include "lib/geometry/mesh_primitives.h"
#include "tests/support/gltf_validator.h"
#include "tests/support/temp_dir.h"
#include "texturing/textured_mesh_io.h"

namespace lutex {
namespace {

// A georeferenced-looking grid (coordinates near 500 km, 6000 km) on one page whose colour is a
// gradient of u, v; the last face untextured.
TexturedMesh GradientGrid(int cells) {
  TexturedMesh textured;
  textured.mesh = MakeHeightFieldMesh([](double x, double y) { return 0.1 * x * y; }, 0.0, 10.0, 0.0, 10.0, cells, cells);
  for (Eigen::Vector3d& v : textured.mesh.vertices) v += Eigen::Vector3d(500000.0, 6000000.0, -40.0);
  textured.pages.emplace_back(64, 64, CV_32FC3);
  for (int row = 0; row < 64; ++row) {
    for (int col = 0; col < 64; ++col) textured.pages[0].at<cv::Vec3f>(row, col) = cv::Vec3f(float(col) / 63.0f, float(row) / 63.0f, 0.5f);
  }
  const std::size_t num_faces = textured.mesh.faces.size();
  textured.face_page.assign(num_faces, 0);
  textured.face_page.back() = -1;
  textured.face_corner_texels.resize(num_faces);
  for (std::size_t f = 0; f < num_faces; ++f) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& v = textured.mesh.vertices[textured.mesh.faces[f][k]];
      textured.face_corner_texels[f][k] = Eigen::Vector2f(float(1.0 + 6.2 * (v.x() - 500000.0)),
                                                          float(1.0 + 6.2 * (v.y() - 6000000.0)));
    }
  }
  return textured;
}

tinygltf::Model ReadGlb(const std::filesystem::path& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, path.string())) << error;
  return model;
}

// The root node's rotation (glTF stores x, y, z, w) and translation.
Eigen::Quaterniond GltfFromModel(const tinygltf::Node& node) {
  EXPECT_EQ(node.rotation.size(), 4u);
  if (node.rotation.size() != 4) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
}

Eigen::Vector3d Translation(const tinygltf::Node& node) {
  EXPECT_EQ(node.translation.size(), 3u);
  if (node.translation.size() != 3) return Eigen::Vector3d::Zero();
  return Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]);
}

// glTF is +Y up: a +Z-up seafloor must stand as a floor (its up on +Y, north on glTF's -Z, the standard
// Z-up to Y-up turn), whatever axis the model calls up.
TEST(GltfExport, TheModelsUpBecomesGltfsUp) {
  testing::TempDir dir;
  TexturedMesh textured = GradientGrid(8);
  for (const Eigen::Vector3d& up : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(0.6, 0, 0.8)}) {
    textured.up = up;
    WriteGltf(textured, dir.path() / "model.glb");
    const tinygltf::Model model = ReadGlb(dir.path() / "model.glb");
    ASSERT_EQ(model.nodes.size(), 1u);
    const Eigen::Quaterniond gltf_from_model = GltfFromModel(model.nodes[0]);
    EXPECT_NEAR(gltf_from_model.norm(), 1.0, 1e-12);
    EXPECT_LT((gltf_from_model * up - Eigen::Vector3d::UnitY()).norm(), 1e-12) << up.transpose();
    if (up.z() == 1.0) {
      EXPECT_LT((gltf_from_model * Eigen::Vector3d::UnitY() - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
      EXPECT_LT((gltf_from_model * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitX()).norm(), 1e-12);
    }
    // The bounds' centre of the mesh, turned the same way, is where the node puts the local positions.
    const Eigen::Vector3d centre(500005.0, 6000005.0, 0.0);
    EXPECT_NEAR((gltf_from_model.inverse() * Translation(model.nodes[0]) - centre).head<2>().norm(), 0.0, 1e-6);
  }
}

// A script can place the model: asset.extras.lutex holds its up and its georeference, in doubles.
TEST(GltfExport, TheGeoreferenceIsRecordedInTheAssetsExtras) {
  testing::TempDir dir;
  TexturedMesh textured = GradientGrid(4);
  textured.georeference.frame = Georeference::Frame::kProjected;
  textured.georeference.crs = "EPSG:32632";
  textured.georeference.origin = {500123.456, 6001234.5, -812.25};
  WriteGltf(textured, dir.path() / "model.glb");
  const tinygltf::Model model = ReadGlb(dir.path() / "model.glb");
  const tinygltf::Value& lutex = model.asset.extras.Get("lutex");
  ASSERT_TRUE(lutex.IsObject());
  const tinygltf::Value& georeference = lutex.Get("georeference");
  EXPECT_EQ(georeference.Get("frame").Get<std::string>(), "projected");
  EXPECT_EQ(georeference.Get("crs").Get<std::string>(), "EPSG:32632");
  ASSERT_EQ(georeference.Get("origin").ArrayLen(), 3u);
  EXPECT_EQ(georeference.Get("origin").Get(0).GetNumberAsDouble(), 500123.456);
  EXPECT_EQ(georeference.Get("origin").Get(1).GetNumberAsDouble(), 6001234.5);
  EXPECT_EQ(georeference.Get("origin").Get(2).GetNumberAsDouble(), -812.25);
  EXPECT_EQ(lutex.Get("up_in_model").Get(2).GetNumberAsDouble(), 1.0);

  textured.georeference = Georeference();
  WriteGltf(textured, dir.path() / "local.glb");
  EXPECT_EQ(ReadGlb(dir.path() / "local.glb").asset.extras.Get("lutex").Get("georeference").Get("frame").Get<std::string>(),
            "none");
}

TEST(GltfExport, GlbHoldsTheMeshLocallyWithTheOriginInTheRootNode) {
  testing::TempDir dir;
  const TexturedMesh textured = GradientGrid(8);
  WriteGltf(textured, dir.path() / "model.glb");
  const tinygltf::Model model = ReadGlb(dir.path() / "model.glb");
  ASSERT_EQ(model.nodes.size(), 1u);
  const Eigen::Vector3d origin = GltfFromModel(model.nodes[0]).inverse() * Translation(model.nodes[0]);
  EXPECT_NEAR(origin.x(), 500005.0, 1e-9);
  EXPECT_NEAR(origin.y(), 6000005.0, 1e-9);
  // One textured primitive and one for the untextured face; both unlit.
  ASSERT_EQ(model.meshes.size(), 1u);
  ASSERT_EQ(model.meshes[0].primitives.size(), 2u);
  EXPECT_EQ(model.extensionsUsed, std::vector<std::string>{"KHR_materials_unlit"});
  for (const tinygltf::Material& material : model.materials) EXPECT_EQ(material.extensions.count("KHR_materials_unlit"), 1u);
  const tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
  EXPECT_EQ(model.materials[primitive.material].pbrMetallicRoughness.baseColorTexture.index, 0);
  EXPECT_EQ(model.images[0].mimeType, "image/png");
  EXPECT_EQ(model.images[0].width, 64);
  EXPECT_EQ(model.accessors[primitive.indices].count, 3 * (textured.mesh.faces.size() - 1));
  // Every vertex + the root origin is a mesh vertex (to float precision of the local coordinates).
  const tinygltf::Accessor& positions = model.accessors[primitive.attributes.at("POSITION")];
  const tinygltf::BufferView& view = model.bufferViews[positions.bufferView];
  const auto* xyz = reinterpret_cast<const float*>(model.buffers[0].data.data() + view.byteOffset + positions.byteOffset);
  double worst = 0.0;
  for (std::size_t i = 0; i < positions.count; ++i) {
    const Eigen::Vector3d world = origin + Eigen::Vector3d(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    double nearest = 1e9;
    for (const Eigen::Vector3d& v : textured.mesh.vertices) nearest = std::min(nearest, (v - world).norm());
    worst = std::max(worst, nearest);
  }
  EXPECT_LT(worst, 1e-5);
}

TEST(GltfExport, TheValidatorFindsNoErrorsOrWarnings) {
  testing::TempDir dir;
  // 8 x 8 cells: 16-bit indices; 260 x 260 cells: 68,121 vertices, 32-bit indices. The validator cannot
  // decode EXT_meshopt_compression (an info says so), but checks everything around it.
  for (const int cells : {8, 260}) {
    const TexturedMesh textured = GradientGrid(cells);
    for (const char* name : {"model.glb", "model.gltf", "model_meshopt.glb"}) {
      const std::filesystem::path path = dir.path() / (std::to_string(cells) + name);
      GltfOptions options;
      options.meshopt_compression = std::string(name).find("meshopt") != std::string::npos;
      WriteGltf(textured, path, options);
      const testing::GltfValidation validation = testing::ValidateGltf(path);
      ASSERT_TRUE(validation.ran) << validation.output;
      EXPECT_TRUE(validation.valid) << path << "\n" << validation.output;
      EXPECT_NE(validation.output.find("errors=0 warnings=0"), std::string::npos) << validation.output;
    }
  }
}

// A GLB's JSON and BIN chunks, read by the spec (glTF 2.0, 4.4), not by the writer's code.
struct GlbChunks {
  nlohmann::json json;
  std::vector<unsigned char> bin;
};

GlbChunks SplitGlb(const std::string& bytes) {
  const auto word = [&](std::size_t at) {
    std::uint32_t value = 0;
    std::memcpy(&value, bytes.data() + at, 4);
    return value;
  };
  GlbChunks chunks;
  EXPECT_EQ(word(0), 0x46546C67u);  // "glTF"
  EXPECT_EQ(word(4), 2u);
  EXPECT_EQ(word(8), bytes.size());
  const std::uint32_t json_length = word(12);
  EXPECT_EQ(word(16), 0x4E4F534Au);  // "JSON"
  chunks.json = nlohmann::json::parse(bytes.substr(20, json_length));
  const std::size_t bin_at = 20 + json_length;
  if (bin_at < bytes.size()) {
    EXPECT_EQ(word(bin_at + 4), 0x004E4942u);  // "BIN"
    chunks.bin.assign(bytes.begin() + static_cast<long>(bin_at + 8), bytes.begin() + static_cast<long>(bin_at + 8 + word(bin_at)));
  }
  return chunks;
}

std::string GlbBytes(const TexturedMesh& textured, bool meshopt) {
  GltfOptions options;
  options.meshopt_compression = meshopt;
  std::ostringstream stream;
  WriteGltf(textured, stream, /*binary=*/true, options);
  return stream.str();
}

// Each triangle of 16- or 32-bit indices rotated to start at its lowest index (same winding): meshopt's
// index codec may rotate triangles.
std::vector<std::uint32_t> CanonicalTriangles(const std::vector<unsigned char>& bytes, std::size_t stride) {
  std::vector<std::uint32_t> indices(bytes.size() / stride);
  for (std::size_t i = 0; i < indices.size(); ++i) {
    std::uint16_t short_index = 0;
    if (stride == 2) {
      std::memcpy(&short_index, bytes.data() + 2 * i, 2);
      indices[i] = short_index;
    } else {
      std::memcpy(&indices[i], bytes.data() + 4 * i, 4);
    }
  }
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    while (indices[t] > indices[t + 1] || indices[t] > indices[t + 2]) std::rotate(&indices[t], &indices[t + 1], &indices[t + 3]);
  }
  return indices;
}

// The bytes buffer view `index` stands for: in buffer 0, or decoded from its EXT_meshopt_compression stream.
std::vector<unsigned char> ViewBytes(const GlbChunks& glb, std::size_t index) {
  const nlohmann::json& view = glb.json["bufferViews"][index];
  const std::size_t length = view["byteLength"];
  std::vector<unsigned char> bytes(length);
  if (!view.contains("extensions")) {
    EXPECT_EQ(view["buffer"], 0);
    const std::size_t offset = view.value("byteOffset", std::size_t{0});
    std::memcpy(bytes.data(), glb.bin.data() + offset, length);
    return bytes;
  }
  const nlohmann::json& meshopt = view["extensions"]["EXT_meshopt_compression"];
  const std::size_t count = meshopt["count"], stride = meshopt["byteStride"];
  EXPECT_EQ(count * stride, length);
  const unsigned char* compressed = glb.bin.data() + meshopt.value("byteOffset", std::size_t{0});
  const std::size_t compressed_length = meshopt["byteLength"];
  const int status = meshopt["mode"] == "TRIANGLES"
                         ? meshopt_decodeIndexBuffer(bytes.data(), count, stride, compressed, compressed_length)
                         : meshopt_decodeVertexBuffer(bytes.data(), count, stride, compressed, compressed_length);
  EXPECT_EQ(status, 0) << "view " << index << " does not decode";
  return bytes;
}

TEST(GltfExport, MeshoptCompressionDecodesToTheSameGeometryInFewerBytes) {
  // 8 x 8 cells: 16-bit indices; 260 x 260 cells: 68,121 vertices, 32-bit indices.
  for (const int cells : {8, 260}) {
    const TexturedMesh textured = GradientGrid(cells);
    const GlbChunks plain = SplitGlb(GlbBytes(textured, false));
    const GlbChunks compressed = SplitGlb(GlbBytes(textured, true));
    const nlohmann::json& json = compressed.json;
    ASSERT_EQ(json["extensionsRequired"], nlohmann::json::array({"EXT_meshopt_compression"}));
    EXPECT_NE(std::find(json["extensionsUsed"].begin(), json["extensionsUsed"].end(), "EXT_meshopt_compression"),
              json["extensionsUsed"].end());
    // Buffer 0 is the BIN chunk; buffer 1 the fallback the decoder fills, with a length and no data.
    ASSERT_EQ(json["buffers"].size(), 2u);
    // (The BIN chunk is padded to 4 bytes.)
    EXPECT_EQ(json["buffers"][0].size(), 1u);
    EXPECT_LE(std::size_t(json["buffers"][0]["byteLength"]), compressed.bin.size());
    EXPECT_GT(std::size_t(json["buffers"][0]["byteLength"]) + 4, compressed.bin.size());
    EXPECT_EQ(json["buffers"][1]["extensions"]["EXT_meshopt_compression"]["fallback"], true);
    EXPECT_FALSE(json["buffers"][1].contains("uri"));
    // Everything but the buffers and views is the uncompressed file's: accessors, meshes, nodes, images.
    for (const char* key : {"accessors", "meshes", "nodes", "materials", "images", "textures", "asset"}) {
      EXPECT_EQ(json[key], plain.json[key]) << key;
    }
    // Every view holds the uncompressed file's bytes (triangles possibly rotated), and the geometry's views
    // are compressed.
    ASSERT_EQ(json["bufferViews"].size(), plain.json["bufferViews"].size());
    std::size_t raw_geometry = 0, compressed_geometry = 0;
    for (std::size_t v = 0; v < json["bufferViews"].size(); ++v) {
      const nlohmann::json& view = json["bufferViews"][v];
      const bool geometry = plain.json["bufferViews"][v].contains("target");
      if (geometry && view["target"] == 34963) {
        const std::size_t stride = view["extensions"]["EXT_meshopt_compression"]["byteStride"];
        EXPECT_EQ(CanonicalTriangles(ViewBytes(compressed, v), stride), CanonicalTriangles(ViewBytes(plain, v), stride))
            << "view " << v << ", " << cells << " cells";
      } else {
        EXPECT_EQ(ViewBytes(compressed, v), ViewBytes(plain, v)) << "view " << v << ", " << cells << " cells";
      }
      EXPECT_EQ(view.contains("extensions"), geometry) << "view " << v;
      if (!geometry) continue;
      EXPECT_EQ(view["buffer"], 1);
      EXPECT_EQ(view.value("byteOffset", std::size_t{0}) % 4, 0u);
      EXPECT_LE(view.value("byteOffset", std::size_t{0}) + std::size_t(view["byteLength"]),
                std::size_t(json["buffers"][1]["byteLength"]));
      // Vertex attributes say their stride; index views must not (glTF 3.6.2.4).
      EXPECT_EQ(view.contains("byteStride"), view["target"] == 34962) << "view " << v;
      raw_geometry += std::size_t(view["byteLength"]);
      compressed_geometry += std::size_t(view["extensions"]["EXT_meshopt_compression"]["byteLength"]);
    }
    std::printf("%d cells: geometry %zu bytes, compressed %zu (%.1f %%)\n", cells, raw_geometry, compressed_geometry,
                100.0 * double(compressed_geometry) / double(raw_geometry));
    // Floats compress less than quantised attributes would: about a third on the large grid.
    EXPECT_LT(double(compressed_geometry), (cells > 100 ? 0.4 : 0.7) * double(raw_geometry)) << cells << " cells";
  }
}

TEST(GltfExport, MeshoptCompressionIsRefusedForFormatsThatCannotHoldIt) {
  GltfOptions meshopt;
  meshopt.meshopt_compression = true;
  EXPECT_NO_THROW(meshopt.CheckOutput("model.glb"));
  for (const char* name : {"model.gltf", "model.obj", "model.ply"}) {
    try {
      meshopt.CheckOutput(name);
      ADD_FAILURE() << name << " was accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(name), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("--meshopt-compression"), std::string::npos) << error.what();
    }
  }
  EXPECT_NO_THROW(GltfOptions{}.CheckOutput("model.gltf"));
  testing::TempDir dir;
  EXPECT_THROW(WriteTexturedMesh(GradientGrid(2), dir.path() / "model.obj", ImageEncoding::kSrgb8, meshopt),
               std::invalid_argument);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << "a refused format left files";
}

TEST(TexturedMeshIo, PlyKeepsFacesAndCornerTexcoordsWithVUp) {
  testing::TempDir dir;
  const TexturedMesh textured = GradientGrid(4);
  const auto written = WriteTexturedMesh(textured, dir.path() / "model.ply", ImageEncoding::kLinear16);
  ASSERT_EQ(written.size(), 2u);
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "model_texture.png"));
  const Mesh mesh = ReadMesh(dir.path() / "model.ply");
  ASSERT_EQ(mesh.faces, textured.mesh.faces);
  ASSERT_EQ(mesh.corner_texcoords.size(), mesh.faces.size());
  const Eigen::Vector2f& texel = textured.face_corner_texels[0][1];
  EXPECT_NEAR(mesh.corner_texcoords[0][1].x(), texel.x() / 64.0f, 1e-6);
  EXPECT_NEAR(mesh.corner_texcoords[0][1].y(), 1.0f - texel.y() / 64.0f, 1e-6);
  EXPECT_EQ(mesh.corner_texcoords.back()[0], Eigen::Vector2f::Zero());  // untextured
  std::ifstream header(dir.path() / "model.ply");
  std::string line;
  bool names_texture = false;
  while (std::getline(header, line) && line != "end_header") names_texture |= line == "comment TextureFile model_texture.png";
  EXPECT_TRUE(names_texture);
}

TEST(TexturedMeshIo, ObjWritesMaterialsAndPagesAndRefusesUnknownFormats) {
  testing::TempDir dir;
  const TexturedMesh textured = GradientGrid(4);
  const auto written = WriteTexturedMesh(textured, dir.path() / "model.obj");
  ASSERT_EQ(written.size(), 3u);  // .obj, .mtl, one page
  for (const auto& path : written) EXPECT_TRUE(std::filesystem::exists(path)) << path;
  std::ifstream material(dir.path() / "model.mtl");
  const std::string text((std::istreambuf_iterator<char>(material)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("map_Kd model_page_0.png"), std::string::npos);
  const Mesh mesh = ReadMesh(dir.path() / "model.obj");
  EXPECT_EQ(mesh.faces.size(), textured.mesh.faces.size());
  EXPECT_THROW(WriteTexturedMesh(textured, dir.path() / "model.fbx"), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "model.fbx"));
}

}  // namespace
}  // namespace lutex
