#include "tests/support/glb_triangles.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

namespace lutex::testing {

namespace {

// Element `i` of a float accessor with `n` components.
Eigen::VectorXd FloatElement(const tinygltf::Model& model, const tinygltf::Accessor& accessor, std::size_t i, int n) {
  const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
  const std::size_t stride = view.byteStride ? view.byteStride : n * sizeof(float);
  const unsigned char* data = model.buffers[view.buffer].data.data() + view.byteOffset + accessor.byteOffset + i * stride;
  Eigen::VectorXd value(n);
  for (int k = 0; k < n; ++k) {
    float component;
    std::memcpy(&component, data + k * sizeof(float), sizeof(float));
    value[k] = component;
  }
  return value;
}

std::uint32_t Index(const tinygltf::Model& model, const tinygltf::Accessor& accessor, std::size_t i) {
  const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
  const unsigned char* data = model.buffers[view.buffer].data.data() + view.byteOffset + accessor.byteOffset;
  if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
    std::uint16_t index;
    std::memcpy(&index, data + 2 * i, 2);
    return index;
  }
  std::uint32_t index;
  std::memcpy(&index, data + 4 * i, 4);
  return index;
}

double Linear(double srgb) { return srgb <= 0.04045 ? srgb / 12.92 : std::pow((srgb + 0.055) / 1.055, 2.4); }

// Bilinear in linear RGB at texture coordinates (u, v), v down, clamped at the border.
Eigen::Vector3d Sample(const GlbImage& image, const Eigen::Vector2d& uv) {
  const double x = uv.x() * image.width - 0.5, y = uv.y() * image.height - 0.5;
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  Eigen::Vector3d colour = Eigen::Vector3d::Zero();
  for (int dy = 0; dy < 2; ++dy) {
    for (int dx = 0; dx < 2; ++dx) {
      const int px = std::clamp(x0 + dx, 0, image.width - 1), py = std::clamp(y0 + dy, 0, image.height - 1);
      const unsigned char* texel = image.pixels.data() + (std::size_t(py) * image.width + px) * image.components;
      const double weight = (dx ? fx : 1.0 - fx) * (dy ? fy : 1.0 - fy);
      for (int k = 0; k < 3; ++k) colour[k] += weight * Linear(texel[k] / 255.0);
    }
  }
  return colour;
}

}  // namespace

Eigen::Vector3d GlbTriangles::AlbedoAt(std::size_t triangle, double b1, double b2) const {
  if (triangle_image[triangle] < 0) return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  const std::array<Eigen::Vector2d, 3>& uv = corner_uv[triangle];
  return Sample(images[triangle_image[triangle]], (1.0 - b1 - b2) * uv[0] + b1 * uv[1] + b2 * uv[2]);
}

GlbTriangles ReadGlbTriangles(const std::filesystem::path& glb) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  GlbTriangles result;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, glb.string())) << glb << ": " << error;
  if (model.nodes.empty() || model.meshes.empty()) {
    ADD_FAILURE() << glb << ": no node or mesh";
    return result;
  }
  const tinygltf::Node& node = model.nodes[0];
  const Eigen::Quaterniond rotation = node.rotation.size() == 4
                                          ? Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2])
                                          : Eigen::Quaterniond::Identity();
  const Eigen::Vector3d translation =
      node.translation.size() == 3 ? Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2])
                                   : Eigen::Vector3d::Zero();
  for (const tinygltf::Image& image : model.images) {
    result.images.push_back({image.width, image.height, image.component, image.image});
  }
  Eigen::Matrix3d tiles_from_gltf;
  tiles_from_gltf << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  for (const tinygltf::Primitive& primitive : model.meshes[node.mesh].primitives) {
    const tinygltf::Accessor& positions = model.accessors[primitive.attributes.at("POSITION")];
    const tinygltf::Accessor& indices = model.accessors[primitive.indices];
    const tinygltf::Accessor* texcoords =
        primitive.attributes.count("TEXCOORD_0") ? &model.accessors[primitive.attributes.at("TEXCOORD_0")] : nullptr;
    int image = -1;
    if (primitive.material >= 0) {
      const int texture = model.materials[primitive.material].pbrMetallicRoughness.baseColorTexture.index;
      if (texture >= 0 && texcoords) image = model.textures[texture].source;
    }
    for (std::size_t v = 0; v < positions.count; ++v) {
      result.vertices_in_tiles_frame.push_back(tiles_from_gltf * (rotation * Eigen::Vector3d(FloatElement(model, positions, v, 3)) + translation));
    }
    for (std::size_t t = 0; t + 2 < indices.count; t += 3) {
      std::array<Eigen::Vector3d, 3> corners;
      std::array<Eigen::Vector2d, 3> uv{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t index = Index(model, indices, t + k);
        const Eigen::Vector3d in_gltf = rotation * Eigen::Vector3d(FloatElement(model, positions, index, 3)) + translation;
        corners[k] = rotation.inverse() * in_gltf;
        if (texcoords) uv[k] = FloatElement(model, *texcoords, index, 2);
      }
      result.corners_in_model.push_back(corners);
      result.corner_uv.push_back(uv);
      result.triangle_image.push_back(image);
      result.centroid_albedo.push_back(result.AlbedoAt(result.corners_in_model.size() - 1, 1.0 / 3.0, 1.0 / 3.0));
    }
  }
  return result;
}

}  // namespace lutex::testing
