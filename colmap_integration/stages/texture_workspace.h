#pragma once

// `lutex texture`: one albedo texture for the mesh of a COLMAP workspace, baked from the restored images
// (texturing/texture_baker.h), written as GLB (or .gltf, .obj, .ply by the output's extension).
//
// Inputs, all checked before anything is written:
//   images       folder with one image per registered image of the model, by the model's name; a restored
//                image written as .png or .exr (lutex restore does so for 16-bit and float output) is
//                found under that extension too. Default: W/lutex/restored when it exists, else W/images
//                (then the texture shows the light and water, not albedo: a warning says so).
//   confidence   IMAGES_confidence/NAME.png (as lutex restore writes them) when that folder exists; the
//                view selection and the fusion then trust each pixel as much as the restoration did.
// Output: default W/lutex/model.glb.

#include <cstddef>
#include <filesystem>
#include <string>
#include <ostream>
#include <string>
#include <vector>

#include "colmap_integration/stages/loaded_dive.h"
#include "lib/image/image_io.h"
#include "texturing/texture_baker.h"

namespace lutex {

struct TextureOptions {
  std::filesystem::path workspace;
  std::filesystem::path mesh;
  std::filesystem::path images;      // empty: see above
  std::filesystem::path confidence;  // empty: IMAGES_confidence when it exists
  bool ignore_confidence = false;  // trust every pixel equally
  std::filesystem::path output;      // empty: W/lutex/model.glb
  ImageEncoding image_encoding = ImageEncoding::kSrgb8;
  // Encoding of OBJ/PLY pages (glTF pages are always 8-bit sRGB).
  ImageEncoding page_encoding = ImageEncoding::kSrgb8;
  TextureBakingOptions baking;
  // The model's up axis for the GLB ("x", "-x", "y", "-y", "z", "-z"), or "auto": opposite the cameras'
  // mean viewing direction, snapped to an axis within 10 degrees (lib/geometry/up_direction.h).
  std::string up_axis = "auto";
  void Check() const;
};

struct TextureSummary {
  std::vector<std::filesystem::path> written;  // the model first
  std::filesystem::path images;
  std::filesystem::path confidence;  // empty when not used
  TextureBakingSummary baking;
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  // in the model's frame; the GLB turns it to +Y
  bool up_from_cameras = false;
  double seconds = 0.0;
};

TextureSummary TextureWorkspace(const TextureOptions& options);
// The same on a dive loaded before (`lutex run` loads it once for every stage): `dive` holds the workspace
// and mesh of `options`.
TextureSummary TextureWorkspace(const TextureOptions& options, const LoadedDive& dive);

// The lines the stage prints when done.
void PrintTextureSummary(std::ostream& out, const TextureSummary& summary);

}  // namespace lutex
