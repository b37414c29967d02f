#include "texturing/textured_ply_export.h"

#include <stdexcept>
#include <string>

#include "lib/geometry/ply_io.h"
#include "lib/util/file_streams.h"
#include "texturing/atlas_page_encoding.h"

namespace lutex {

namespace fs = std::filesystem;

void WriteTexturedPly(const TexturedMesh& textured, const fs::path& path, ImageEncoding page_encoding) {
  if (path.extension() != ".ply") throw std::invalid_argument(path.string() + ": a PLY file must end in .ply");
  if (textured.pages.size() > 1) {
    throw std::runtime_error(path.string() + ": the atlas has " + std::to_string(textured.pages.size()) +
                             " pages but a textured PLY holds one; write .glb or .obj, or raise the page size");
  }
  const std::string texture_name = path.stem().string() + "_texture.png";
  Mesh mesh = textured.mesh;
  mesh.corner_texcoords.assign(mesh.faces.size(), {Eigen::Vector2f::Zero(), Eigen::Vector2f::Zero(), Eigen::Vector2f::Zero()});
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (textured.face_page[f] < 0) continue;
    const cv::Mat& page = textured.pages[textured.face_page[f]];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2f& texel = textured.face_corner_texels[f][k];
      mesh.corner_texcoords[f][k] = Eigen::Vector2f(texel.x() / float(page.cols), 1.0f - texel.y() / float(page.rows));
    }
  }
  if (!textured.pages.empty()) {
    const std::vector<unsigned char> png = EncodeAtlasPage(textured.pages[0], page_encoding);
    WriteFileAtomically(path.parent_path() / texture_name, std::ios::binary, [&png](std::ostream& stream) {
      stream.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
    });
  }
  WriteFileAtomically(path, std::ios::binary,
                      [&](std::ostream& stream) { WritePly(mesh, stream, {"TextureFile " + texture_name}); });
}

}  // namespace lutex
