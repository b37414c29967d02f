#include "colmap_integration/stages/simulate_workspace.h"

#include <chrono>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "colmap_integration/io/colmap_array.h"
#include "colmap_integration/stages/output_policy.h"
#include "lib/model/scene_description.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "lib/geometry/mesh_io.h"
#include "lib/lut/lut_file.h"
#include "lib/lut/lut_slab_images.h"
#include "lib/model/sparse_points.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/model/synthetic_seafloor.h"
#include "lib/util/file_streams.h"
#include "lib/util/logging.h"
#include "lib/util/progress.h"
#include "lib/util/option_error.h"

namespace lutex {

namespace fs = std::filesystem;

void SimulateOptions::Check() const {
  if (scene.empty()) throw OptionError("{scene} is required");
  if (output.empty()) throw OptionError("{output} is required");
}

SimulateSummary SimulateWorkspace(const SimulateOptions& options) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  SceneDescription scene = ReadSceneDescription(options.scene);
  InputsAndOutputs paths;
  paths.AddInput(options.scene, "the scene description");
  paths.AddInput(scene.mesh_path, "the scene's mesh");
  paths.AddInput(scene.texture_path, "the scene's albedo texture");
  paths.AddOutput(options.output);
  paths.Check();
  paths.RemoveStaleTemporaries();
  scene.simulator.num_threads = options.num_threads;
  const Mesh mesh = scene.mesh_path.empty() ? MakeSyntheticSeafloor(scene.seafloor) : ReadMesh(scene.mesh_path);
  SurfaceAlbedo albedo = SurfaceAlbedo::Constant(scene.constant_albedo);
  if (scene.albedo_kind == SceneDescription::AlbedoKind::kVertexColors) {
    if (mesh.vertex_colors.empty()) {
      throw std::runtime_error(options.scene.string() + ": albedo is vertex_colors but the mesh has none");
    }
    albedo = SurfaceAlbedo::FromVertexColors(mesh);
  } else if (scene.albedo_kind == SceneDescription::AlbedoKind::kFaceColors) {
    if (mesh.face_colors.empty()) {
      throw std::runtime_error(options.scene.string() + ": albedo is face_colors but the mesh has none");
    }
    albedo = SurfaceAlbedo::FromFaceColors(mesh);
  } else if (scene.albedo_kind == SceneDescription::AlbedoKind::kTexture) {
    albedo = SurfaceAlbedo::FromTexture(mesh, ReadLinearImage(scene.texture_path, scene.texture_encoding));
  }
  const Simulator simulator(mesh, scene.rig, scene.water, albedo, scene.simulator);
  const CameraRays rays(scene.camera, options.num_threads);
  const BackscatterTable backscatter = simulator.MakeBackscatterTable(rays);
  LogInfo() << "simulating " << scene.poses.size() << " images of " << mesh.NumFaces() << " faces, "
            << scene.rig.lights.size() << " lights, " << (scene.water.IsAir() ? "in air" : "in water");

  SparseModel model;
  model.cameras[scene.camera.camera_id] = scene.camera;
  const fs::path& root = options.output;
  ProgressReporter progress("simulate", scene.poses.size(), "images");
  GeometryMapsOptions depth_only;
  depth_only.normal = false;
  depth_only.num_threads = options.num_threads;
  for (std::size_t i = 0; i < scene.poses.size(); ++i) {
    const NamedPose& pose = scene.poses[i];
    const cv::Mat radiance = simulator.Render(rays, backscatter, pose.cam_from_world);
    WriteLinearImage(ApplySensor(radiance, scene.sensor, i), root / "images" / pose.name, scene.output_encoding);
    WriteLinearImage(simulator.RenderAlbedo(rays, pose.cam_from_world), root / "ground_truth" / "albedo" / pose.name,
                     ImageEncoding::kLinear16);
    WriteColmapArray(ReplaceNanWithZero(simulator.RenderGeometry(rays, pose.cam_from_world, depth_only).depth),
                     root / "ground_truth" / "depth" / (pose.name + ".bin"));
    Image image;
    image.image_id = static_cast<std::uint32_t>(i + 1);
    image.camera_id = scene.camera.camera_id;
    image.name = pose.name;
    image.cam_from_world = pose.cam_from_world;
    model.images[image.image_id] = image;
    progress.Advance();
  }
  progress.Finish();
  if (scene.sparse_points_per_image > 0) {
    SparsePointsOptions points;
    points.points_per_image = scene.sparse_points_per_image;
    points.noise = scene.sparse_point_noise;
    points.num_threads = options.num_threads;
    const std::size_t added = AddSimulatedSparsePoints(RaycastScene(mesh), points, &model);
    LogInfo() << "simulate: " << added << " sparse 3-D points with their tracks";
  }
  WriteSparseModel(model, root / "sparse" / "0", scene.sparse_format);
  WriteMesh(mesh, root / "scene" / "mesh.ply");
  // The true LUT describes the images, so it includes the sensor's exposure (noise and blur average out).
  FrustumLut true_lut = simulator.TrueLut(scene.camera, scene.lut_grid);
  for (int n = 0; n < true_lut.grid().NumNodes(); ++n) {
    true_lut.node(n).alpha *= scene.sensor.exposure;
    true_lut.node(n).beta *= scene.sensor.exposure;
  }
  WriteLut(true_lut, root / "ground_truth" / "true.lut");
  // Each image's exposure relative to the true LUT's (sensor.exposure_variation).
  nlohmann::json factors = nlohmann::json::object();
  for (std::size_t i = 0; i < scene.poses.size(); ++i) factors[scene.poses[i].name] = ExposureFactor(scene.sensor, i);
  WriteFileAtomically(root / "ground_truth" / "exposure_factors.json", std::ios::out,
                      [&factors](std::ostream& stream) { stream << factors.dump(2) << "\n"; });
  WriteLutSlabImages(true_lut, root / "ground_truth" / "true_lut_slabs");

  SimulateSummary summary;
  summary.num_images = scene.poses.size();
  summary.num_faces = mesh.NumFaces();
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.seconds_per_image = summary.seconds / static_cast<double>(summary.num_images);
  return summary;
}

}  // namespace lutex
