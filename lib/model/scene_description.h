#pragma once

// The scene description that `lutex simulate` renders: a JSON file (documented in the README, examples in
// examples/scenes/). Every field has a default except the camera; unknown keys are errors, so a typo
// never passes silently. Paths are relative to the description file.
//
// {
//   "mesh": "seafloor.ply"  or  {"synthetic": {"size": [10, 8], "cell_size": 0.05, "relief": 0.15,
//                                              "boulders": 2, "patch_size": 0.4, "seed": 7}},
//   "albedo": "vertex_colors" | "face_colors" | {"constant": [r, g, b]} | {"texture": "albedo.png", "encoding": "linear16"},
//   "camera": {"model": "PINHOLE", "width": 640, "height": 480, "params": [320, 320, 320, 240]},
//   "survey": {"pattern": "lawnmower", "x": [-3.5, 3.5], "y": [-1.5, 1.5], "lines": 3,
//              "images_per_line": 8, "altitude": 2.0}
//        or "poses": [{"name": "a.png", "qvec": [w, x, y, z], "tvec": [x, y, z]}, ...]  (cam_from_world),
//   "lights": [{"position": [-0.4, 0, 0], "direction": [0, 0, 1], "intensity": [1, 1, 1] or "power_W": 15,
//               "profile": "isotropic" | "cosine_power" (exponent) | "gaussian" (sigma_deg) |
//                          "cycles_spot" (spot_size_deg, spot_blend)}],
//   "water": "air" | {"absorption": [r, g, b], "scattering": [r, g, b], "g": 0.9},
//   "sensor": {"exposure": 1, "exposure_variation": 0, "blur_px": 0, "shot_noise": 0, "read_noise": 0, "seed": 1},
//   "output": {"encoding": "srgb8" | "linear16", "sparse_format": "text" | "binary",
//              "sparse_points": 0, "sparse_point_noise": 0}  (3-D points per image, as SfM gives them:
//              lib/model/sparse_points.h; their position noise in metres),
//   "lut": {"nx": 40, "ny": 30, "nz": 10, "z_near": 0.5, "z_far": 5, "spacing": "inverse_z" | "z"},
//   "simulator": {"backscatter_steps": 96, "max_range": 30, "shadows": true, "forward_scatter": false}
// }

#include <filesystem>
#include <string>
#include <vector>

#include "lib/geometry/camera.h"
#include "lib/geometry/rigid3d.h"
#include "lib/geometry/sparse_model.h"
#include "lib/image/image_io.h"
#include "lib/lut/frustum_lut.h"
#include "lib/model/light_rig.h"
#include "lib/model/sensor.h"
#include "lib/model/simulator.h"
#include "lib/model/synthetic_seafloor.h"
#include "lib/model/water.h"

namespace lutex {

struct NamedPose {
  std::string name;
  Rigid3d cam_from_world;
};

struct SceneDescription {
  std::filesystem::path mesh_path;  // empty: synthetic seafloor
  SyntheticSeafloorOptions seafloor;
  enum class AlbedoKind { kVertexColors, kFaceColors, kConstant, kTexture } albedo_kind = AlbedoKind::kVertexColors;
  Eigen::Vector3d constant_albedo = Eigen::Vector3d::Constant(0.5);
  std::filesystem::path texture_path;
  ImageEncoding texture_encoding = ImageEncoding::kLinear16;
  Camera camera;
  std::vector<NamedPose> poses;
  LightRig rig;
  Water water;
  SensorOptions sensor;
  ImageEncoding output_encoding = ImageEncoding::kSrgb8;
  SparseFormat sparse_format = SparseFormat::kText;
  int sparse_points_per_image = 0;
  double sparse_point_noise = 0.0;
  FrustumLutGrid lut_grid;
  SimulatorOptions simulator;
};

// Throws std::runtime_error naming the file and the offending key.
SceneDescription ReadSceneDescription(const std::filesystem::path& path);

}  // namespace lutex
