#include "texturing/obj_export.h"

#include <iomanip>
#include <stdexcept>
#include <string>

#include "lib/util/file_streams.h"
#include "texturing/atlas_page_encoding.h"

namespace lutex {

namespace fs = std::filesystem;

void WriteObj(const TexturedMesh& textured, const fs::path& path, ImageEncoding page_encoding) {
  if (path.extension() != ".obj") throw std::invalid_argument(path.string() + ": an OBJ file must end in .obj");
  const Mesh& mesh = textured.mesh;
  const std::string stem = path.stem().string();
  fs::path material_path = path;
  material_path.replace_extension(".mtl");
  std::vector<std::string> page_names;
  for (std::size_t p = 0; p < textured.pages.size(); ++p) {
    page_names.push_back(stem + "_page_" + std::to_string(p) + ".png");
    const std::vector<unsigned char> png = EncodeAtlasPage(textured.pages[p], page_encoding);
    WriteFileAtomically(path.parent_path() / page_names.back(), std::ios::binary, [&png](std::ostream& stream) {
      stream.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
    });
  }
  WriteFileAtomically(material_path, std::ios::out, [&](std::ostream& stream) {
    stream << "# lutex albedo texture: unlit (the texture is albedo)\n";
    for (std::size_t p = 0; p < page_names.size(); ++p) {
      stream << "newmtl albedo_page_" << p << "\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nillum 0\nmap_Kd " << page_names[p]
             << "\n\n";
    }
    stream << "newmtl untextured\nKa 0 0 0\nKd 0.5 0.5 0.5\nKs 0 0 0\nillum 0\n";
  });
  WriteFileAtomically(path, std::ios::out, [&](std::ostream& stream) {
    stream << "# written by lutex: " << mesh.vertices.size() << " vertices, " << mesh.faces.size() << " faces\n"
           << "mtllib " << material_path.filename().string() << "\n"
           << std::setprecision(12);
    for (const Eigen::Vector3d& v : mesh.vertices) stream << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
    stream << std::setprecision(7);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      const int page = textured.face_page[f];
      if (page < 0) continue;
      for (const Eigen::Vector2f& texel : textured.face_corner_texels[f]) {
        stream << "vt " << texel.x() / float(textured.pages[page].cols) << " "
               << 1.0f - texel.y() / float(textured.pages[page].rows) << "\n";
      }
    }
    // Faces grouped by material; texture coordinates are numbered in face order.
    std::vector<std::size_t> first_texcoord(mesh.faces.size(), 0);
    std::size_t next = 1;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      if (textured.face_page[f] < 0) continue;
      first_texcoord[f] = next;
      next += 3;
    }
    for (int page = -1; page < static_cast<int>(textured.pages.size()); ++page) {
      stream << "usemtl " << (page < 0 ? std::string("untextured") : "albedo_page_" + std::to_string(page)) << "\n";
      for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        if (textured.face_page[f] != page) continue;
        stream << "f";
        for (int k = 0; k < 3; ++k) {
          stream << " " << mesh.faces[f][k] + 1;
          if (page >= 0) stream << "/" << first_texcoord[f] + k;
        }
        stream << "\n";
      }
    }
  });
}

}  // namespace lutex
