#pragma once

// `lutex texture`: one albedo texture for the mesh of a COLMAP workspace, baked from the restored images
// (texturing/texture_baker.h), written as GLB (or .gltf, .obj, .ply by the output's extension).
//
// Inputs (workspace_views.h: the restored images by default, and their confidence maps) are all checked
// before anything is written.
// Output: default W/lutex/model.glb.

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "colmap_integration/stages/loaded_dive.h"
#include "colmap_integration/stages/model_up.h"
#include "colmap_integration/stages/workspace_georeference.h"
#include "colmap_integration/stages/workspace_views.h"
#include "lib/image/image_io.h"
#include "texturing/gltf_export.h"
#include "texturing/texture_baker.h"

namespace lutex {

struct TextureOptions {
  std::filesystem::path workspace;
  std::filesystem::path mesh;
  WorkspaceViewsOptions views;   // the images to texture from and their confidence
  std::filesystem::path output;  // empty: W/lutex/model.glb
  // Encoding of OBJ/PLY pages (glTF pages are always 8-bit sRGB).
  ImageEncoding page_encoding = ImageEncoding::kSrgb8;
  GltfOptions gltf;  // for a .glb output: EXT_meshopt_compression
  TextureBakingOptions baking;
  // The stage refuses to start when its memory estimate (stage_memory.h) exceeds this; 0: the machine's
  // available memory. The estimate counts the fusion's budget (baking.fusion.memory_limit_bytes) and the
  // faces' tables as parts.
  std::size_t memory_limit_bytes = 0;
  // The model's up axis for the GLB ("x", "-x", "y", "-y", "z", "-z"), or "auto": opposite the cameras'
  // mean viewing direction, snapped to an axis within 10 degrees (lib/geometry/up_direction.h).
  std::string up_axis = "auto";
  // Recorded in the GLB (options, else W/georef.json); with one, up is the frame's +z unless up_axis says.
  GeoreferenceOptions georeference;
  void Check() const;
};

struct TextureSummary {
  std::vector<std::filesystem::path> written;  // the model first
  std::filesystem::path images;
  std::filesystem::path confidence;  // empty when not used
  TextureBakingSummary baking;
  ModelUp up;  // the GLB turns it to +Y
  WorkspaceGeoreference georeference;
  double seconds = 0.0;
};

TextureSummary TextureWorkspace(const TextureOptions& options);
// The same on a dive loaded before (`lutex run` loads it once for every stage): `dive` holds the workspace
// and mesh of `options`.
TextureSummary TextureWorkspace(const TextureOptions& options, const LoadedDive& dive);

// The lines the stage prints when done.
void PrintTextureSummary(std::ostream& out, const TextureSummary& summary);

}  // namespace lutex
