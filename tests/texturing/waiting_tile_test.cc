#include "texturing/waiting_tile.h"

#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "lib/geometry/mesh_primitives.h"
#include "tests/support/temp_dir.h"
#include "texturing/view_selection.h"

namespace lutex {
namespace {

// A tile as a parent would be made from it: a curved patch with shading normals, two pages of texels
// (one holding a NaN and a negative zero, whose bits must survive too), an untextured face and a face
// no view saw.
WaitingTile MakeTile() {
  WaitingTile tile;
  tile.geometry.mesh =
      MakeHeightFieldMesh([](double x, double y) { return 0.1 * x * x - 0.05 * y + 1e5; }, -1.0, 1.0, -0.5, 0.5, 7, 5);
  Mesh& mesh = tile.geometry.mesh;
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    mesh.vertex_normals.push_back(Eigen::Vector3f(unit(random), unit(random), 1.0f).normalized());
    tile.geometry.source_vertex.push_back(static_cast<std::uint32_t>(3 * v + 1));
  }
  for (const cv::Size size : {cv::Size(37, 21), cv::Size(5, 8)}) {
    cv::Mat page(size, CV_32FC3);
    for (int r = 0; r < page.rows; ++r) {
      for (int c = 0; c < page.cols; ++c) page.at<cv::Vec3f>(r, c) = cv::Vec3f(unit(random), unit(random), unit(random));
    }
    tile.halved_texture.pages.push_back(page);
  }
  tile.halved_texture.pages[0].at<cv::Vec3f>(3, 4) = cv::Vec3f(std::numeric_limits<float>::quiet_NaN(), -0.0f, 1e-30f);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    tile.halved_texture.face_page.push_back(f == 2 ? -1 : static_cast<int>(f % 2));
    tile.halved_texture.face_corner_texels.push_back(
        {Eigen::Vector2f(unit(random) * 5, unit(random) * 8), Eigen::Vector2f(1.5f, 2.25f), Eigen::Vector2f(0.5f, 7.75f)});
    tile.view_of_face.push_back(f == 2 ? kNoView : static_cast<std::uint32_t>(f % 4));
  }
  tile.halved_texture.mesh = mesh;
  return tile;
}

bool SameBits(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return false;
  for (int r = 0; r < a.rows; ++r) {
    if (std::memcmp(a.ptr(r), b.ptr(r), a.cols * a.elemSize()) != 0) return false;
  }
  return true;
}

TEST(WaitingTile, ReadBackItIsTheTileToTheBit) {
  const testing::TempDir dir;
  const WaitingTile tile = MakeTile();
  WriteWaitingTile(tile, dir.path() / "0_1.tile");
  const WaitingTile read = ReadWaitingTile(dir.path() / "0_1.tile");

  const Mesh& mesh = tile.geometry.mesh;
  ASSERT_EQ(read.geometry.mesh.vertices.size(), mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    EXPECT_EQ(read.geometry.mesh.vertices[v], mesh.vertices[v]);  // at 1e5 m, every bit of the double
    EXPECT_EQ(read.geometry.mesh.vertex_normals[v], mesh.vertex_normals[v]);
  }
  EXPECT_EQ(read.geometry.mesh.faces, mesh.faces);
  EXPECT_TRUE(read.geometry.mesh.vertex_colors.empty());
  EXPECT_EQ(read.geometry.source_vertex, tile.geometry.source_vertex);
  ASSERT_EQ(read.halved_texture.pages.size(), 2u);
  for (std::size_t p = 0; p < 2; ++p) EXPECT_TRUE(SameBits(read.halved_texture.pages[p], tile.halved_texture.pages[p]));
  EXPECT_EQ(read.halved_texture.face_page, tile.halved_texture.face_page);
  EXPECT_EQ(read.halved_texture.face_corner_texels, tile.halved_texture.face_corner_texels);
  EXPECT_EQ(read.view_of_face, tile.view_of_face);
  // The texture's mesh is the geometry's: it samples the same as the tile written.
  EXPECT_EQ(read.halved_texture.mesh.faces, mesh.faces);
  for (std::uint32_t f : {0u, 5u, 11u}) {
    EXPECT_EQ(read.halved_texture.AlbedoAt(f, 0.2f, 0.3f), tile.halved_texture.AlbedoAt(f, 0.2f, 0.3f));
  }
}

TEST(WaitingTile, AFileCutShortOrOfAnotherKindIsRefusedNamingIt) {
  const testing::TempDir dir;
  const std::filesystem::path path = dir.path() / "0_2.tile";
  WriteWaitingTile(MakeTile(), path);
  const auto whole = std::filesystem::file_size(path);
  for (const std::uintmax_t size : {whole - 1, whole / 2, std::uintmax_t{30}}) {
    std::filesystem::resize_file(path, size);
    try {
      ReadWaitingTile(path);
      ADD_FAILURE() << "a file cut to " << size << " bytes was read";
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("truncated"), std::string::npos) << error.what();
    }
  }
  std::ofstream(path) << "ply\nformat ascii 1.0\n";
  EXPECT_THROW(ReadWaitingTile(path), std::runtime_error);
  EXPECT_THROW(ReadWaitingTile(dir.path() / "missing.tile"), std::runtime_error);
}

}  // namespace
}  // namespace lutex
