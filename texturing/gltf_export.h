#pragma once

// glTF 2.0 export of a textured mesh, with tinygltf: what map viewers (Cesium, three.js, Blender, QGIS 3D)
// load.
//
// - One primitive per atlas page (positions, normals, TEXCOORD_0, indices of 16 or 32 bits as the
//   primitive needs) with its own material; faces no view saw go to one primitive without texture, in a
//   neutral grey.
// - Materials are unlit (KHR_materials_unlit): the texture is albedo, lighting it again in a viewer
//   would darken it twice. Base colour textures are 8-bit sRGB PNG, as the glTF spec requires.
// - Vertex positions are stored relative to the centre of the mesh bounds, in float; the root node's
//   translation (double precision in JSON) puts them back, so georeferenced models keep their precision.
// - glTF is +Y up (spec 3.4): the root node's rotation turns the model's up (TexturedMesh::up) to +Y, so a
//   viewer shows a seafloor as a floor, not a wall. glTF = rotation * model; a script wanting the model's
//   own coordinates applies the node's inverse.
// - asset.extras.lutex records the model's frame so a viewer or script can place it:
//     {"up_in_model": [0, 0, 1], "georeference": {"frame": "projected", "crs": "EPSG:32632",
//      "origin": [500123.0, 6001234.0, -812.5]}}
//   (georeference.h for the frames; "frame": "none" without one). The model's coordinates are
//   the root node's inverse applied to glTF's.
// - Vertices are split where one mesh vertex has different texture coordinates in different charts.
//
// - With GltfOptions::meshopt_compression, positions, normals, texture coordinates and indices are
//   compressed losslessly with EXT_meshopt_compression (meshopt_streams.h), listed as required: viewers
//   without a decoder refuse the file rather than show it wrong. CesiumJS decodes it natively, three.js
//   with GLTFLoader.setMeshoptDecoder. The texture pages, most of a textured model's bytes, stay PNG.
//
// .glb: one binary file, images embedded through buffer views (glb_container.h). .gltf: JSON with buffers
// and images embedded as base64 data URIs (one self-contained file, about a third larger).

#include <filesystem>
#include <ostream>

#include "texturing/textured_mesh.h"

namespace lutex {

struct GltfOptions {
  // EXT_meshopt_compression for the geometry (.glb only).
  bool meshopt_compression = false;
  // Throws std::invalid_argument naming `path` when it cannot hold what these options ask for; commands
  // call it before any work.
  void CheckOutput(const std::filesystem::path& path) const;
};

// Throws std::runtime_error naming `path` when it cannot be written; writes a temporary file and renames
// it, so a failure leaves no partial output.
void WriteGltf(const TexturedMesh& textured, const std::filesystem::path& path, const GltfOptions& options = {});

// The same into a stream (binary GLB or JSON).
void WriteGltf(const TexturedMesh& textured, std::ostream& stream, bool binary, const GltfOptions& options = {});

}  // namespace lutex
