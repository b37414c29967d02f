#include "lib/geometry/mesh_io.h"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "lib/geometry/mesh_primitives.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

void WriteText(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

std::string AsciiPly(const std::string& face_property, const std::string& extra_vertex_line = "",
                     const std::string& faces = "3 0 1 2\n3 0 2 3\n") {
  return "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 4\nproperty float x\nproperty float y\n"
         "property float z\nproperty float quality\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
         "element face 2\nproperty list uchar int " + face_property + "\nend_header\n"
         "0 0 0 0.5 255 0 0\n1 0 0 0.5 0 255 0\n1 1 0 0.5 0 0 255\n" + (extra_vertex_line.empty() ? "0 1 0 0.5 10 20 30\n" : extra_vertex_line) +
         faces;
}

TEST(MeshIo, ReadsAsciiPlyWithVertexIndicesColoursAndExtraProperties) {
  testing::TempDir dir;
  WriteText(dir.path() / "a.ply", AsciiPly("vertex_indices"));
  const Mesh mesh = ReadMesh(dir.path() / "a.ply");
  ASSERT_EQ(mesh.NumVertices(), 4u);
  ASSERT_EQ(mesh.NumFaces(), 2u);
  EXPECT_EQ(mesh.vertices[2], Eigen::Vector3d(1, 1, 0));
  ASSERT_EQ(mesh.vertex_colors.size(), 4u);
  EXPECT_EQ(int(mesh.vertex_colors[3][2]), 30);
  EXPECT_EQ(mesh.faces[1], (Mesh::Face{0, 2, 3}));
}

// Some tools name the face list `vertex_index` (singular).
TEST(MeshIo, ReadsPlyWithVertexIndexSingular) {
  testing::TempDir dir;
  WriteText(dir.path() / "b.ply", AsciiPly("vertex_index"));
  const Mesh mesh = ReadMesh(dir.path() / "b.ply");
  EXPECT_EQ(mesh.NumFaces(), 2u);
}

TEST(MeshIo, BinaryPlyRoundTripKeepsDoublePrecisionAndAttributes) {
  testing::TempDir dir;
  // Georeferenced-like coordinates where float would lose centimetres.
  Mesh mesh = MakeHeightFieldMesh([](double x, double y) { return 0.1 * x - 0.05 * y; }, 512345.0, 512349.0,
                                  6012345.0, 6012348.0, 4, 3);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    mesh.vertex_colors.emplace_back(static_cast<std::uint8_t>(i), 7, 200);
  }
  WriteMesh(mesh, dir.path() / "terrain.ply");
  const Mesh read = ReadMesh(dir.path() / "terrain.ply");
  ASSERT_EQ(read.NumVertices(), mesh.NumVertices());
  ASSERT_EQ(read.NumFaces(), mesh.NumFaces());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    EXPECT_EQ(read.vertices[i], mesh.vertices[i]);
    EXPECT_EQ(read.vertex_colors[i], mesh.vertex_colors[i]);
    EXPECT_EQ(read.vertex_texcoords[i], mesh.vertex_texcoords[i]);
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) EXPECT_EQ(read.faces[f], mesh.faces[f]);
}

// Face colours (as MeshLab writes them) survive reading, degenerate-face removal and writing.
TEST(MeshIo, FaceColoursRoundTrip) {
  testing::TempDir dir;
  WriteText(dir.path() / "f.ply",
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 3\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\n"
            "property uchar blue\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 200 10 20\n3 0 0 1 1 2 3\n"
            "3 0 2 3 30 40 250\n");
  const Mesh mesh = ReadMesh(dir.path() / "f.ply");
  ASSERT_EQ(mesh.NumFaces(), 2u);  // the middle face is degenerate
  ASSERT_EQ(mesh.face_colors.size(), 2u);
  EXPECT_EQ(int(mesh.face_colors[1][2]), 250);
  WriteMesh(mesh, dir.path() / "g.ply");
  EXPECT_EQ(ReadMesh(dir.path() / "g.ply").face_colors, mesh.face_colors);
}

TEST(MeshIo, ReadsObjOffAndStlAndTriangulatesQuads) {
  testing::TempDir dir;
  WriteText(dir.path() / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  EXPECT_EQ(ReadMesh(dir.path() / "quad.obj").NumFaces(), 2u);
  WriteText(dir.path() / "quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  EXPECT_EQ(ReadMesh(dir.path() / "quad.off").NumFaces(), 2u);
  const Mesh box = MakeBoxMesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3));
  WriteMesh(box, dir.path() / "box.stl");
  const Mesh read = ReadMesh(dir.path() / "box.stl");
  EXPECT_EQ(read.NumFaces(), 12u);
  EXPECT_EQ(read.BoundsMax(), Eigen::Vector3d(1, 2, 3));
}

void ExpectReadError(const fs::path& path, const std::string& expected_part) {
  try {
    ReadMesh(path);
    FAIL() << "no error for " << path;
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(expected_part), std::string::npos) << message;
  }
}

TEST(MeshIo, BadFilesGiveOneErrorNamingTheFile) {
  testing::TempDir dir;
  ExpectReadError(dir.path() / "missing.ply", "no such file");
  WriteText(dir.path() / "empty.ply", "");
  ExpectReadError(dir.path() / "empty.ply", "empty");
  WriteText(dir.path() / "garbage.ply", "this is not a mesh at all\n");
  ExpectReadError(dir.path() / "garbage.ply", "not a PLY file");
  WriteText(dir.path() / "garbage.obj", "\x01\x02 not an obj");
  ExpectReadError(dir.path() / "garbage.obj", "no faces");
  WriteText(dir.path() / "points.xyz", "0 0 0\n");
  ExpectReadError(dir.path() / "points.xyz", "unsupported mesh format");
  WriteText(dir.path() / "nan.ply", AsciiPly("vertex_indices", "nan 1 0 0.5 1 2 3\n"));
  ExpectReadError(dir.path() / "nan.ply", "not finite");
  WriteText(dir.path() / "no_faces.obj", "v 0 0 0\nv 1 0 0\n");
  ExpectReadError(dir.path() / "no_faces.obj", "no faces");
}

TEST(MeshIo, TruncatedBinaryPlyIsAnError) {
  testing::TempDir dir;
  const Mesh mesh = MakeHeightFieldMesh([](double, double) { return 0.0; }, 0, 1, 0, 1, 10, 10);
  WriteMesh(mesh, dir.path() / "full.ply");
  const auto size = fs::file_size(dir.path() / "full.ply");
  fs::copy_file(dir.path() / "full.ply", dir.path() / "cut.ply");
  fs::resize_file(dir.path() / "cut.ply", size / 2);
  ExpectReadError(dir.path() / "cut.ply", "");
}

TEST(MeshIo, OutOfRangeFaceIndexIsAnError) {
  testing::TempDir dir;
  WriteText(dir.path() / "range.ply", AsciiPly("vertex_indices", "", "3 0 1 2\n3 0 2 9\n"));
  ExpectReadError(dir.path() / "range.ply", "");
}

// A NaN list length or vertex index (found by fuzz/ply_fuzzer) or float colour (found reviewing the reader) was cast to an
// integer, undefined behaviour; an element without properties was "read" once per record, up to 2^63 times.
TEST(MeshIo, NanLengthIndexOrColourIsAnErrorAndAnEmptyElementIsReadAtOnce) {
  testing::TempDir dir;
  WriteText(dir.path() / "nan_length.ply", AsciiPly("vertex_indices", "", "nan 0 1 2\n3 0 2 3\n"));
  ExpectReadError(dir.path() / "nan_length.ply", "PLY face vertex_indices has an implausible list length");
  // A NaN vertex index passed the range test, whose comparisons are all false for NaN (fuzz/ply_fuzzer, CI).
  WriteText(dir.path() / "nan_index.ply", AsciiPly("vertex_indices", "", "3 0 nan 2\n3 0 2 3\n"));
  ExpectReadError(dir.path() / "nan_index.ply", "PLY face 0 has a negative, huge or NaN vertex index");
  WriteText(dir.path() / "nan.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            "property float red\nproperty float green\nproperty float blue\nelement face 1\n"
            "property list uchar int vertex_indices\nend_header\n0 0 0 nan 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n3 0 1 2\n");
  ExpectReadError(dir.path() / "nan.ply", "PLY vertex colour is not a number");
  WriteText(dir.path() / "empty_element.ply",
            "ply\nformat ascii 1.0\nelement nothing 9000000000000000000\nelement vertex 3\nproperty float x\n"
            "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(ReadMesh(dir.path() / "empty_element.ply").faces.size(), 1u);
}

TEST(MeshIo, DegenerateFacesAreDropped) {
  Mesh mesh = MakeHeightFieldMesh([](double, double) { return 0.0; }, 0, 1, 0, 1, 1, 1);
  mesh.faces.push_back({0, 0, 1});                   // repeated vertex
  mesh.vertices.emplace_back(2.0, 0.0, 0.0);          // collinear with vertices 0 and 1
  mesh.faces.push_back({0, 1, static_cast<std::uint32_t>(mesh.vertices.size() - 1)});
  mesh.vertex_texcoords.clear();
  EXPECT_EQ(mesh.RemoveDegenerateFaces(), 2u);
  EXPECT_EQ(mesh.NumFaces(), 2u);
}

}  // namespace
}  // namespace lutex
