#include "lib/geometry/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <fstream>
#include <stdexcept>

// GCC 12 reports a false -Wmaybe-uninitialized inside OpenMesh's property templates instantiated here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#pragma GCC diagnostic pop

#include "lib/geometry/ply_io.h"
#include "lib/util/atomic_output.h"
#include "lib/util/file_streams.h"
#include "lib/util/logging.h"

namespace lutex {
namespace {

// Double-precision points: see mesh.h.
struct DoublePrecisionTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
  typedef OpenMesh::Vec2f TexCoord2D;
  typedef OpenMesh::Vec3uc Color;
};
using OpenMeshTriMesh = OpenMesh::TriMesh_ArrayKernelT<DoublePrecisionTraits>;

std::string LowerExtension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

void CheckSupportedExtension(const std::filesystem::path& path) {
  const std::string extension = LowerExtension(path);
  if (extension != ".ply" && extension != ".obj" && extension != ".off" && extension != ".stl") {
    throw std::runtime_error(path.string() + ": unsupported mesh format '" + extension +
                             "' (lutex reads .ply, .obj, .off and .stl)");
  }
}

// OpenMesh reports problems on its own streams; lutex reports them itself, once, with the file name.
void SilenceOpenMesh() {
  static const bool silenced = [] {
    omerr().disable();
    omout().disable();
    omlog().disable();
    return true;
  }();
  (void)silenced;
}

// OBJ, OFF and STL through OpenMesh.
Mesh ReadMeshWithOpenMesh(const std::filesystem::path& path) {
  SilenceOpenMesh();
  OpenMeshTriMesh source;
  source.request_vertex_colors();
  source.request_vertex_texcoords2D();
  source.request_halfedge_texcoords2D();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexColor |
                                  OpenMesh::IO::Options::VertexTexCoord |
                                  OpenMesh::IO::Options::FaceTexCoord;
  if (!OpenMesh::IO::read_mesh(source, path.string(), options)) {
    throw std::runtime_error("not a readable " + LowerExtension(path).substr(1) +
                             " mesh (the file is corrupt, truncated or of another format)");
  }

  Mesh mesh;
  mesh.vertices.reserve(source.n_vertices());
  for (const auto vertex : source.vertices()) {
    const auto& p = source.point(vertex);
    mesh.vertices.emplace_back(p[0], p[1], p[2]);
  }
  if (options.check(OpenMesh::IO::Options::VertexColor)) {
    for (const auto vertex : source.vertices()) {
      const auto& c = source.color(vertex);
      mesh.vertex_colors.emplace_back(c[0], c[1], c[2]);
    }
  }
  if (options.check(OpenMesh::IO::Options::VertexTexCoord)) {
    for (const auto vertex : source.vertices()) {
      const auto& t = source.texcoord2D(vertex);
      mesh.vertex_texcoords.emplace_back(t[0], t[1]);
    }
  }
  const bool has_corner_texcoords = options.check(OpenMesh::IO::Options::FaceTexCoord);
  mesh.faces.reserve(source.n_faces());
  for (const auto face : source.faces()) {
    Mesh::Face indices{};
    std::array<Eigen::Vector2f, 3> corners;
    int corner = 0;
    for (const auto halfedge : source.fh_range(face)) {
      if (corner == 3) break;
      indices[corner] = static_cast<std::uint32_t>(source.to_vertex_handle(halfedge).idx());
      const auto& t = source.texcoord2D(halfedge);
      corners[corner] = Eigen::Vector2f(t[0], t[1]);
      ++corner;
    }
    mesh.faces.push_back(indices);
    if (has_corner_texcoords) mesh.corner_texcoords.push_back(corners);
  }
  return mesh;
}

}  // namespace

Mesh ReadMesh(const std::filesystem::path& path) {
  CheckSupportedExtension(path);
  if (std::filesystem::is_regular_file(path) && std::filesystem::file_size(path) == 0) {
    throw std::runtime_error(path.string() + ": the mesh file is empty");
  }
  Mesh mesh = ParseFile(path, std::ios::binary, [&path](std::istream& stream) {
    return LowerExtension(path) == ".ply" ? ReadPly(stream) : ReadMeshWithOpenMesh(path);
  });
  mesh.Check(path.string());
  const std::size_t removed = mesh.RemoveDegenerateFaces();
  if (removed > 0) {
    LogInfo() << path.string() << ": dropped " << removed << " degenerate faces (repeated vertex or zero area)";
  }
  if (mesh.faces.empty()) throw std::runtime_error(path.string() + ": every face of the mesh is degenerate");
  LogDebug() << "read mesh " << path.string() << ": " << mesh.NumFaces() << " faces";
  return mesh;
}

void WriteMesh(const Mesh& mesh, const std::filesystem::path& path) {
  SilenceOpenMesh();
  CheckSupportedExtension(path);
  mesh.Check("mesh to write to " + path.string());
  if (LowerExtension(path) == ".ply") {
    WriteFileAtomically(path, std::ios::binary, [&mesh](std::ostream& stream) { WritePly(mesh, stream); });
    return;
  }
  OpenMeshTriMesh target;
  OpenMesh::IO::Options options;
  if (!mesh.vertex_colors.empty()) {
    target.request_vertex_colors();
    options += OpenMesh::IO::Options::VertexColor;
  }
  if (!mesh.vertex_texcoords.empty()) {
    target.request_vertex_texcoords2D();
    options += OpenMesh::IO::Options::VertexTexCoord;
  }
  std::vector<OpenMeshTriMesh::VertexHandle> handles;
  handles.reserve(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d& v = mesh.vertices[i];
    const auto handle = target.add_vertex(OpenMeshTriMesh::Point(v.x(), v.y(), v.z()));
    if (!mesh.vertex_colors.empty()) {
      const auto& c = mesh.vertex_colors[i];
      target.set_color(handle, OpenMeshTriMesh::Color(c[0], c[1], c[2]));
    }
    if (!mesh.vertex_texcoords.empty()) {
      target.set_texcoord2D(handle, OpenMeshTriMesh::TexCoord2D(mesh.vertex_texcoords[i].x(),
                                                                 mesh.vertex_texcoords[i].y()));
    }
    handles.push_back(handle);
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Mesh::Face& face = mesh.faces[f];
    if (!target.add_face(handles[face[0]], handles[face[1]], handles[face[2]]).is_valid()) {
      throw std::runtime_error(path.string() + ": face " + std::to_string(f) +
                               " is non-manifold, which this format's writer cannot store (write .ply instead)");
    }
  }
  if (LowerExtension(path) == ".stl") {
    options += OpenMesh::IO::Options::Binary;
  }
  AtomicOutputFile output(path);
  errno = 0;
  if (!OpenMesh::IO::write_mesh(target, output.temporary_path().string(), options, 17)) {
    throw std::runtime_error(DescribeWriteFailure(path, errno, "the mesh writer failed"));
  }
  output.Commit();
}

}  // namespace lutex
