#include "texturing/textured_mesh_io.h"

#include <stdexcept>
#include <string>

#include "texturing/gltf_export.h"
#include "texturing/obj_export.h"
#include "texturing/textured_ply_export.h"

namespace lutex {

namespace fs = std::filesystem;

void CheckTexturedMeshPath(const fs::path& path) {
  const std::string extension = path.extension().string();
  if (extension != ".glb" && extension != ".gltf" && extension != ".obj" && extension != ".ply") {
    throw std::invalid_argument(path.string() + ": unknown model format '" + extension +
                                "' (use .glb, .gltf, .obj or .ply)");
  }
}

std::vector<fs::path> WriteTexturedMesh(const TexturedMesh& textured, const fs::path& path, ImageEncoding page_encoding,
                                        const GltfOptions& gltf) {
  CheckTexturedMeshPath(path);
  gltf.CheckOutput(path);
  const std::string extension = path.extension().string();
  std::vector<fs::path> written{path};
  if (extension == ".glb" || extension == ".gltf") {
    WriteGltf(textured, path, gltf);
  } else if (extension == ".obj") {
    WriteObj(textured, path, page_encoding);
    fs::path material = path;
    written.push_back(material.replace_extension(".mtl"));
    for (std::size_t p = 0; p < textured.pages.size(); ++p) {
      written.push_back(path.parent_path() / (path.stem().string() + "_page_" + std::to_string(p) + ".png"));
    }
  } else {
    WriteTexturedPly(textured, path, page_encoding);
    written.push_back(path.parent_path() / (path.stem().string() + "_texture.png"));
  }
  return written;
}

}  // namespace lutex
