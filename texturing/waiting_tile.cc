#include "texturing/waiting_tile.h"

#include <fstream>
#include <stdexcept>
#include <string>

#include "lib/util/binary_io.h"

namespace lutex {

namespace {

constexpr char kMagic[] = "lutex-waiting-tile 1\n";

void WriteMesh(std::ostream& out, const Mesh& mesh) {
  WriteBinaryArray(out, mesh.vertices);
  WriteBinaryArray(out, mesh.faces);
  WriteBinaryArray(out, mesh.vertex_colors);
  WriteBinaryArray(out, mesh.vertex_texcoords);
  WriteBinaryArray(out, mesh.vertex_normals);
  WriteBinaryArray(out, mesh.face_colors);
  WriteBinaryArray(out, mesh.corner_texcoords);
}

void ReadMesh(std::istream& in, Mesh& mesh) {
  ReadBinaryArray(in, "the vertices", mesh.vertices);
  ReadBinaryArray(in, "the faces", mesh.faces);
  ReadBinaryArray(in, "the vertex colours", mesh.vertex_colors);
  ReadBinaryArray(in, "the vertex texture coordinates", mesh.vertex_texcoords);
  ReadBinaryArray(in, "the vertex normals", mesh.vertex_normals);
  ReadBinaryArray(in, "the face colours", mesh.face_colors);
  ReadBinaryArray(in, "the corner texture coordinates", mesh.corner_texcoords);
}

}  // namespace

void WriteWaitingTile(const WaitingTile& tile, const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(kMagic, sizeof(kMagic) - 1);
  WriteMesh(out, tile.geometry.mesh);
  WriteBinaryArray(out, tile.geometry.source_vertex);
  const TexturedMesh& texture = tile.halved_texture;
  WriteBinary(out, static_cast<std::uint64_t>(texture.pages.size()));
  for (const cv::Mat& page : texture.pages) {
    if (page.type() != CV_32FC3) throw std::invalid_argument("waiting tile: a page that is not CV_32FC3");
    WriteBinary(out, static_cast<std::int32_t>(page.rows));
    WriteBinary(out, static_cast<std::int32_t>(page.cols));
    for (int row = 0; row < page.rows; ++row) {
      out.write(page.ptr<char>(row), static_cast<std::streamsize>(page.cols * page.elemSize()));
    }
  }
  WriteBinaryArray(out, texture.face_page);
  WriteBinaryArray(out, texture.face_corner_texels);
  WriteBinaryArray(out, tile.view_of_face);
  out.flush();
  if (!out) throw std::runtime_error(path.string() + ": could not write a waiting tile (is the disk full?)");
}

WaitingTile ReadWaitingTile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open the waiting tile");
  WaitingTile tile;
  try {
    std::string magic(sizeof(kMagic) - 1, '\0');
    in.read(magic.data(), static_cast<std::streamsize>(magic.size()));
    if (!in || magic != kMagic) throw std::runtime_error("not a waiting tile");
    ReadMesh(in, tile.geometry.mesh);
    ReadBinaryArray(in, "the source vertices", tile.geometry.source_vertex);
    TexturedMesh& texture = tile.halved_texture;
    const auto num_pages = ReadBinary<std::uint64_t>(in, "the page count");
    for (std::uint64_t p = 0; p < num_pages; ++p) {
      const auto rows = ReadBinary<std::int32_t>(in, "a page's size");
      const auto cols = ReadBinary<std::int32_t>(in, "a page's size");
      if (rows < 0 || cols < 0 ||
          std::uint64_t(rows) * std::uint64_t(cols) * 3 * sizeof(float) > BytesLeft(in).value_or(0)) {
        ThrowTruncated("a page");
      }
      cv::Mat page(rows, cols, CV_32FC3);
      for (int row = 0; row < page.rows; ++row) {
        in.read(page.ptr<char>(row), static_cast<std::streamsize>(page.cols * page.elemSize()));
      }
      if (!in) ThrowTruncated("a page");
      texture.pages.push_back(page);
    }
    ReadBinaryArray(in, "the faces' pages", texture.face_page);
    ReadBinaryArray(in, "the faces' texel corners", texture.face_corner_texels);
    ReadBinaryArray(in, "the faces' views", tile.view_of_face);
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(path.string() + ": " + error.what() + " (a waiting tile of a tiled bake)");
  }
  tile.halved_texture.mesh = tile.geometry.mesh;
  return tile;
}

}  // namespace lutex
