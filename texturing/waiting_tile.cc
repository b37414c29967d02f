#include "texturing/waiting_tile.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <string>

namespace lutex {

namespace {

constexpr char kMagic[] = "lutex-waiting-tile 1\n";

// Arrays of plain values (Eigen's fixed-size vectors included: their bytes are their coefficients).
template <typename T>
void WriteArray(std::ostream& out, const std::vector<T>& values) {
  const std::uint64_t count = values.size();
  out.write(reinterpret_cast<const char*>(&count), sizeof(count));
  out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(count * sizeof(T)));
}

template <typename T>
void ReadArray(std::istream& in, std::uint64_t bytes_left, std::vector<T>& values) {
  std::uint64_t count = 0;
  in.read(reinterpret_cast<char*>(&count), sizeof(count));
  if (!in || count > bytes_left / sizeof(T)) throw std::runtime_error("truncated");
  values.resize(count);
  in.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(count * sizeof(T)));
  if (!in) throw std::runtime_error("truncated");
}

void WriteMesh(std::ostream& out, const Mesh& mesh) {
  WriteArray(out, mesh.vertices);
  WriteArray(out, mesh.faces);
  WriteArray(out, mesh.vertex_colors);
  WriteArray(out, mesh.vertex_texcoords);
  WriteArray(out, mesh.vertex_normals);
  WriteArray(out, mesh.face_colors);
  WriteArray(out, mesh.corner_texcoords);
}

void ReadMesh(std::istream& in, std::uint64_t bytes, Mesh& mesh) {
  ReadArray(in, bytes, mesh.vertices);
  ReadArray(in, bytes, mesh.faces);
  ReadArray(in, bytes, mesh.vertex_colors);
  ReadArray(in, bytes, mesh.vertex_texcoords);
  ReadArray(in, bytes, mesh.vertex_normals);
  ReadArray(in, bytes, mesh.face_colors);
  ReadArray(in, bytes, mesh.corner_texcoords);
}

}  // namespace

void WriteWaitingTile(const WaitingTile& tile, const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(kMagic, sizeof(kMagic) - 1);
  WriteMesh(out, tile.geometry.mesh);
  WriteArray(out, tile.geometry.source_vertex);
  const TexturedMesh& texture = tile.halved_texture;
  const std::uint64_t num_pages = texture.pages.size();
  out.write(reinterpret_cast<const char*>(&num_pages), sizeof(num_pages));
  for (const cv::Mat& page : texture.pages) {
    if (page.type() != CV_32FC3) throw std::invalid_argument("waiting tile: a page that is not CV_32FC3");
    const std::int32_t size[2] = {page.rows, page.cols};
    out.write(reinterpret_cast<const char*>(size), sizeof(size));
    for (int row = 0; row < page.rows; ++row) {
      out.write(page.ptr<char>(row), static_cast<std::streamsize>(page.cols * page.elemSize()));
    }
  }
  WriteArray(out, texture.face_page);
  WriteArray(out, texture.face_corner_texels);
  WriteArray(out, tile.view_of_face);
  out.flush();
  if (!out) throw std::runtime_error(path.string() + ": could not write a waiting tile (is the disk full?)");
}

WaitingTile ReadWaitingTile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open the waiting tile");
  in.seekg(0, std::ios::end);
  const std::uint64_t bytes = static_cast<std::uint64_t>(std::max<std::streamoff>(in.tellg(), 0));
  in.seekg(0);
  WaitingTile tile;
  try {
    std::string magic(sizeof(kMagic) - 1, '\0');
    in.read(magic.data(), static_cast<std::streamsize>(magic.size()));
    if (!in || magic != kMagic) throw std::runtime_error("not a waiting tile");
    ReadMesh(in, bytes, tile.geometry.mesh);
    ReadArray(in, bytes, tile.geometry.source_vertex);
    TexturedMesh& texture = tile.halved_texture;
    std::uint64_t num_pages = 0;
    in.read(reinterpret_cast<char*>(&num_pages), sizeof(num_pages));
    if (!in || num_pages > bytes) throw std::runtime_error("truncated");
    for (std::uint64_t p = 0; p < num_pages; ++p) {
      std::int32_t size[2] = {0, 0};
      in.read(reinterpret_cast<char*>(size), sizeof(size));
      if (!in || size[0] < 0 || size[1] < 0 ||
          std::uint64_t(size[0]) * std::uint64_t(size[1]) * 3 * sizeof(float) > bytes) {
        throw std::runtime_error("truncated");
      }
      cv::Mat page(size[0], size[1], CV_32FC3);
      for (int row = 0; row < page.rows; ++row) {
        in.read(page.ptr<char>(row), static_cast<std::streamsize>(page.cols * page.elemSize()));
      }
      if (!in) throw std::runtime_error("truncated");
      texture.pages.push_back(page);
    }
    ReadArray(in, bytes, texture.face_page);
    ReadArray(in, bytes, texture.face_corner_texels);
    ReadArray(in, bytes, tile.view_of_face);
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(path.string() + ": " + error.what() + " (a waiting tile of a tiled bake)");
  }
  tile.halved_texture.mesh = tile.geometry.mesh;
  return tile;
}

}  // namespace lutex
