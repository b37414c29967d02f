#include "texturing/gltf_export.h"

#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "lib/util/file_streams.h"
#include "texturing/atlas_page_encoding.h"
#include "texturing/glb_container.h"
#include "texturing/gltf_frame.h"
#include "texturing/meshopt_streams.h"

namespace lutex {

namespace {

constexpr int kArrayBuffer = 34962;         // GL_ARRAY_BUFFER
constexpr int kElementArrayBuffer = 34963;  // GL_ELEMENT_ARRAY_BUFFER
constexpr int kFloat = 5126, kUnsignedShort = 5123, kUnsignedInt = 5125;
constexpr int kLinear = 9729, kLinearMipmapLinear = 9987, kClampToEdge = 33071;
constexpr const char* kMeshopt = "EXT_meshopt_compression";

// A buffer view whose bytes are meshopt-compressed in buffer 0 (meshopt_streams.h for the layout).
struct CompressedView {
  int buffer_view = 0;
  std::size_t byte_offset = 0, byte_length = 0;  // of the compressed bytes in buffer 0
  std::size_t byte_stride = 0, count = 0;
  const char* mode = "";
};

// The model as tinygltf holds it, and what tinygltf 2.7 cannot write: the compressed views' extension
// objects and the fallback buffer (buffer 1) they decode into.
struct BuiltModel {
  tinygltf::Model model;
  bool meshopt = false;
  std::vector<CompressedView> compressed;
  std::size_t fallback_bytes = 0;
};

// Appends bytes to buffer 0 at a 4-byte boundary; returns their offset.
std::size_t AppendToBuffer(tinygltf::Model& model, const void* data, std::size_t size) {
  std::vector<unsigned char>& buffer = model.buffers[0].data;
  while (buffer.size() % 4 != 0) buffer.push_back(0);
  const std::size_t offset = buffer.size();
  const auto* bytes = static_cast<const unsigned char*>(data);
  buffer.insert(buffer.end(), bytes, bytes + size);
  return offset;
}

// Raw bytes in buffer 0 as a new buffer view; returns its index.
int AddBufferView(tinygltf::Model& model, const void* data, std::size_t size, int target) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = AppendToBuffer(model, data, size);
  view.byteLength = size;
  if (target != 0) view.target = target;
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

// A view of `count` elements of `stride` bytes: raw, or meshopt-compressed when the model asks for it
// (vertex attributes with the vertex codec, `triangles` with the index codec from `indices`).
int AddGeometryView(BuiltModel& built, const void* data, std::size_t count, std::size_t stride, int target,
                    const std::vector<std::uint32_t>* triangles = nullptr, std::size_t vertex_count = 0) {
  if (!built.meshopt) return AddBufferView(built.model, data, count * stride, target);
  const std::vector<unsigned char> bytes = triangles != nullptr ? EncodeMeshoptTriangles(*triangles, vertex_count)
                                                                : EncodeMeshoptAttributes(data, count, stride);
  CompressedView compressed;
  compressed.byte_offset = AppendToBuffer(built.model, bytes.data(), bytes.size());
  compressed.byte_length = bytes.size();
  compressed.byte_stride = stride;
  compressed.count = count;
  compressed.mode = triangles != nullptr ? "TRIANGLES" : "ATTRIBUTES";
  tinygltf::BufferView view;
  view.buffer = 1;
  built.fallback_bytes = (built.fallback_bytes + 3) / 4 * 4;
  view.byteOffset = built.fallback_bytes;
  view.byteLength = count * stride;
  if (triangles == nullptr) view.byteStride = stride;  // index views must not have one (glTF 3.6.2.4)
  view.target = target;
  built.fallback_bytes += view.byteLength;
  built.model.bufferViews.push_back(view);
  compressed.buffer_view = static_cast<int>(built.model.bufferViews.size() - 1);
  built.compressed.push_back(compressed);
  return compressed.buffer_view;
}

int AddAccessor(tinygltf::Model& model, int buffer_view, int component_type, int type, std::size_t count) {
  tinygltf::Accessor accessor;
  accessor.bufferView = buffer_view;
  accessor.componentType = component_type;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

int AddMaterial(tinygltf::Model& model, int texture, const std::string& name) {
  tinygltf::Material material;
  material.name = name;
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 1.0;
  if (texture >= 0) {
    material.pbrMetallicRoughness.baseColorTexture.index = texture;
  } else {
    material.pbrMetallicRoughness.baseColorFactor = {0.5, 0.5, 0.5, 1.0};
  }
  material.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
  model.materials.push_back(material);
  return static_cast<int>(model.materials.size() - 1);
}

// asset.extras.lutex: the model's up and georeference (gltf_export.h).
tinygltf::Value FrameExtras(const TexturedMesh& textured) {
  const auto vector = [](const Eigen::Vector3d& v) {
    return tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(v.x()), tinygltf::Value(v.y()), tinygltf::Value(v.z())});
  };
  tinygltf::Value::Object georeference;
  georeference["frame"] = tinygltf::Value(FrameName(textured.georeference.frame));
  if (textured.georeference.IsSet()) {
    georeference["origin"] = vector(textured.georeference.origin);
    if (!textured.georeference.crs.empty()) georeference["crs"] = tinygltf::Value(textured.georeference.crs);
  }
  tinygltf::Value::Object lutex;
  lutex["up_in_model"] = vector(textured.up.normalized());
  lutex["georeference"] = tinygltf::Value(georeference);
  tinygltf::Value::Object extras;
  extras["lutex"] = tinygltf::Value(lutex);
  return tinygltf::Value(extras);
}

// Unit vertex normals: the mesh's own, else area-weighted face normals.
std::vector<Eigen::Vector3f> VertexNormals(const Mesh& mesh) {
  std::vector<Eigen::Vector3d> sums(mesh.vertices.size(), Eigen::Vector3d::Zero());
  if (mesh.vertex_normals.size() == mesh.vertices.size()) {
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) sums[v] = mesh.vertex_normals[v].cast<double>();
  } else {
    for (const Mesh::Face& face : mesh.faces) {
      const Eigen::Vector3d n =
          (mesh.vertices[face[1]] - mesh.vertices[face[0]]).cross(mesh.vertices[face[2]] - mesh.vertices[face[0]]);
      for (std::uint32_t v : face) sums[v] += n;
    }
  }
  std::vector<Eigen::Vector3f> normals(sums.size());
  for (std::size_t v = 0; v < sums.size(); ++v) {
    const double length = sums[v].norm();
    normals[v] = length > 0.0 && std::isfinite(length) ? Eigen::Vector3f((sums[v] / length).cast<float>())
                                                        : Eigen::Vector3f::UnitZ();
  }
  return normals;
}

// One primitive: the faces of one page (page -1: the untextured faces).
void AddPrimitive(BuiltModel& built, tinygltf::Mesh& gltf_mesh, const TexturedMesh& textured, int page,
                  const std::vector<Eigen::Vector3f>& normals, const Eigen::Vector3d& origin, int material) {
  tinygltf::Model& model = built.model;
  const Mesh& mesh = textured.mesh;
  const bool with_texcoords = page >= 0;
  const float page_width = with_texcoords ? static_cast<float>(textured.pages[page].cols) : 1.0f;
  const float page_height = with_texcoords ? static_cast<float>(textured.pages[page].rows) : 1.0f;
  // A vertex of the primitive per (mesh vertex, texture coordinate).
  std::map<std::tuple<std::uint32_t, float, float>, std::uint32_t> index_of;
  std::vector<float> positions, vertex_normals, texcoords;
  std::vector<std::uint32_t> indices;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (textured.face_page[f] != page) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.faces[f][k];
      float u = 0.0f, w = 0.0f;
      if (with_texcoords) {
        u = textured.face_corner_texels[f][k].x() / page_width;
        w = textured.face_corner_texels[f][k].y() / page_height;
      }
      const auto [it, inserted] = index_of.emplace(std::make_tuple(v, u, w), static_cast<std::uint32_t>(index_of.size()));
      if (inserted) {
        const Eigen::Vector3d local = mesh.vertices[v] - origin;
        for (int c = 0; c < 3; ++c) positions.push_back(static_cast<float>(local[c]));
        for (int c = 0; c < 3; ++c) vertex_normals.push_back(normals[v][c]);
        texcoords.push_back(u);
        texcoords.push_back(w);
      }
      indices.push_back(it->second);
    }
  }
  if (indices.empty()) return;
  const std::size_t num_vertices = positions.size() / 3;
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.material = material;
  const int position_accessor =
      AddAccessor(model, AddGeometryView(built, positions.data(), num_vertices, 3 * sizeof(float), kArrayBuffer),
                  kFloat, TINYGLTF_TYPE_VEC3, num_vertices);
  std::vector<double> low(3, std::numeric_limits<double>::infinity()), high(3, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    low[i % 3] = std::min<double>(low[i % 3], positions[i]);
    high[i % 3] = std::max<double>(high[i % 3], positions[i]);
  }
  model.accessors[position_accessor].minValues = low;
  model.accessors[position_accessor].maxValues = high;
  primitive.attributes["POSITION"] = position_accessor;
  primitive.attributes["NORMAL"] =
      AddAccessor(model, AddGeometryView(built, vertex_normals.data(), num_vertices, 3 * sizeof(float), kArrayBuffer),
                  kFloat, TINYGLTF_TYPE_VEC3, num_vertices);
  if (with_texcoords) {
    primitive.attributes["TEXCOORD_0"] =
        AddAccessor(model, AddGeometryView(built, texcoords.data(), num_vertices, 2 * sizeof(float), kArrayBuffer),
                    kFloat, TINYGLTF_TYPE_VEC2, num_vertices);
  }
  if (num_vertices <= 65535) {
    const std::vector<std::uint16_t> short_indices(indices.begin(), indices.end());
    primitive.indices = AddAccessor(
        model, AddGeometryView(built, short_indices.data(), indices.size(), 2, kElementArrayBuffer, &indices, num_vertices),
        kUnsignedShort, TINYGLTF_TYPE_SCALAR, indices.size());
  } else {
    primitive.indices = AddAccessor(
        model, AddGeometryView(built, indices.data(), indices.size(), 4, kElementArrayBuffer, &indices, num_vertices),
        kUnsignedInt, TINYGLTF_TYPE_SCALAR, indices.size());
  }
  gltf_mesh.primitives.push_back(primitive);
}

BuiltModel BuildModel(const TexturedMesh& textured, const GltfOptions& options) {
  const Mesh& mesh = textured.mesh;
  BuiltModel built;
  tinygltf::Model& model = built.model;
  model.asset.version = "2.0";
  model.asset.generator = "lutex";
  model.asset.extras = FrameExtras(textured);
  model.extensionsUsed.push_back("KHR_materials_unlit");
  model.buffers.emplace_back();
  if (options.meshopt_compression) {
    built.meshopt = true;
    model.extensionsUsed.push_back(kMeshopt);
    model.extensionsRequired.push_back(kMeshopt);
    model.buffers.emplace_back();  // the fallback buffer: written by WriteGltf
  }
  tinygltf::Sampler sampler;
  sampler.magFilter = kLinear;
  sampler.minFilter = kLinearMipmapLinear;
  sampler.wrapS = kClampToEdge;
  sampler.wrapT = kClampToEdge;
  model.samplers.push_back(sampler);

  const Eigen::Vector3d origin = 0.5 * (mesh.BoundsMin() + mesh.BoundsMax());
  const std::vector<Eigen::Vector3f> normals = VertexNormals(mesh);
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = "albedo";
  for (std::size_t p = 0; p < textured.pages.size(); ++p) {
    const std::vector<unsigned char> png = EncodeAtlasPage(textured.pages[p]);
    tinygltf::Image image;
    image.name = "albedo_page_" + std::to_string(p);
    image.mimeType = "image/png";
    image.bufferView = AddBufferView(model, png.data(), png.size(), 0);
    model.images.push_back(image);
    tinygltf::Texture texture;
    texture.source = static_cast<int>(model.images.size() - 1);
    texture.sampler = 0;
    model.textures.push_back(texture);
    const int material = AddMaterial(model, static_cast<int>(model.textures.size() - 1), image.name);
    AddPrimitive(built, gltf_mesh, textured, static_cast<int>(p), normals, origin, material);
  }
  if (textured.NumTexturedFaces() < mesh.faces.size()) {
    AddPrimitive(built, gltf_mesh, textured, -1, normals, origin, AddMaterial(model, -1, "untextured"));
  }
  model.meshes.push_back(gltf_mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = "lutex model";
  // glTF is +Y up: the node turns the model's up to +Y (gltf_frame.h). Positions stay local and in the
  // model's frame.
  const Eigen::Quaterniond gltf_from_model = GltfFromModel(textured.up);
  const Eigen::Vector3d origin_in_gltf = gltf_from_model * origin;
  node.rotation = {gltf_from_model.x(), gltf_from_model.y(), gltf_from_model.z(), gltf_from_model.w()};
  node.translation = {origin_in_gltf.x(), origin_in_gltf.y(), origin_in_gltf.z()};
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return built;
}

// The GLB's JSON: tinygltf's, with buffer 0 as the BIN chunk and the meshopt extension objects added.
std::string GlbJson(const BuiltModel& built, std::size_t bin_bytes) {
  std::ostringstream text;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&built.model, text, /*prettyPrint=*/false, /*writeBinary=*/false)) {
    throw std::runtime_error("glTF export: writing failed");
  }
  nlohmann::json document = nlohmann::json::parse(text.str());
  document["buffers"][0] = {{"byteLength", bin_bytes}};
  if (built.meshopt) {
    document["buffers"][1] = {{"byteLength", built.fallback_bytes}, {"extensions", {{kMeshopt, {{"fallback", true}}}}}};
    for (const CompressedView& view : built.compressed) {
      document["bufferViews"][view.buffer_view]["extensions"][kMeshopt] = {
          {"buffer", 0},           {"byteOffset", view.byte_offset}, {"byteLength", view.byte_length},
          {"byteStride", view.byte_stride}, {"count", view.count}, {"mode", view.mode}};
    }
  }
  return document.dump();
}

}  // namespace

void GltfOptions::CheckOutput(const std::filesystem::path& path) const {
  if (meshopt_compression && path.extension() != ".glb") {
    throw std::invalid_argument(path.string() + ": EXT_meshopt_compression (--meshopt-compression) is written into .glb "
                                "files only");
  }
}

void WriteGltf(const TexturedMesh& textured, std::ostream& stream, bool binary, const GltfOptions& options) {
  if (textured.face_page.size() != textured.mesh.faces.size() ||
      textured.face_corner_texels.size() != textured.mesh.faces.size()) {
    throw std::invalid_argument("glTF export: the texture does not match the mesh's faces");
  }
  if (options.meshopt_compression && !binary) {
    throw std::invalid_argument("glTF export: EXT_meshopt_compression is written into .glb files only");
  }
  BuiltModel built = BuildModel(textured, options);
  if (binary) {
    // The BIN chunk is written from buffer 0 itself, not from a copy (glb_container.h).
    const std::vector<unsigned char> bin = std::move(built.model.buffers[0].data);
    built.model.buffers[0].data.clear();
    WriteGlb(stream, GlbJson(built, bin.size()), bin);
    return;
  }
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&built.model, stream, /*prettyPrint=*/true, /*writeBinary=*/false) || !stream) {
    throw std::runtime_error("glTF export: writing failed");
  }
}

void WriteGltf(const TexturedMesh& textured, const std::filesystem::path& path, const GltfOptions& options) {
  const std::string extension = path.extension().string();
  if (extension != ".glb" && extension != ".gltf") {
    throw std::invalid_argument(path.string() + ": a glTF file must end in .glb or .gltf");
  }
  options.CheckOutput(path);
  WriteFileAtomically(path, std::ios::binary, [&](std::ostream& stream) {
    try {
      WriteGltf(textured, stream, extension == ".glb", options);
    } catch (const std::exception& error) {
      throw std::runtime_error(path.string() + ": " + error.what());
    }
  });
}

}  // namespace lutex
