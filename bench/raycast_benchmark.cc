// Ray-casting speed: lutex's RaycastScene::Render against a bare Embree loop over the same primary rays
// (rtcIntersect16 packets of 4x4 pixels, depth only, same threads), measured in the same run. Reported
// as rays per second and the ratio bare / lutex. Not a test: speed is never asserted.
//
//   raycast_benchmark [--width 4000] [--height 3000] [--cells 710] [--repeats 3] [--num-threads 0]
//
// The mesh is a height field of cells x cells x 2 triangles (710 -> 1.01 M faces) seen from 3 m.

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "bench/bench_options.h"
#include "lib/geometry/look_at.h"
#include "lib/geometry/mesh_primitives.h"
#include "lib/raycast/raycast_scene.h"
#include "lib/raycast/embree_ray_packet.h"
#include "lib/util/parallel_for.h"

namespace {

// The baseline: Embree alone, rays generated inline for a pinhole camera, depth written to a buffer.
double BareEmbreeSeconds(const lutex::Mesh& mesh, const lutex::Camera& camera, const lutex::Rigid3d& cam_from_world,
                         int num_threads, std::vector<float>* depth) {
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.vertices.size()));
  auto* indices = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), mesh.faces.size()));
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) vertices[3 * i + k] = static_cast<float>(mesh.vertices[i][k]);
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) std::memcpy(indices + 3 * f, mesh.faces[f].data(), 12);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);

  const int width = static_cast<int>(camera.width), height = static_cast<int>(camera.height);
  const Eigen::Matrix3f world_from_cam = cam_from_world.rotation.toRotationMatrix().transpose().cast<float>();
  const Eigen::Vector3f centre = cam_from_world.TargetOriginInSource().cast<float>();
  const float fx = static_cast<float>(camera.FocalLengthX()), fy = static_cast<float>(camera.FocalLengthY());
  const float cx = static_cast<float>(camera.PrincipalPointX()), cy = static_cast<float>(camera.PrincipalPointY());
  depth->assign(static_cast<std::size_t>(width) * height, 0.0f);
  const auto start = std::chrono::steady_clock::now();
  lutex::ParallelFor(static_cast<std::size_t>((height + 3) / 4), num_threads, [&](std::size_t block_row) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    alignas(64) RTCRayHit16 packet;
    alignas(64) int valid[16];
    for (int block_col = 0; block_col < (width + 3) / 4; ++block_col) {
      for (int lane = 0; lane < 16; ++lane) {
        const int col = block_col * 4 + lane % 4, row = static_cast<int>(block_row) * 4 + lane / 4;
        valid[lane] = col < width && row < height ? -1 : 0;
        const Eigen::Vector3f direction =
            world_from_cam * Eigen::Vector3f((static_cast<float>(col) + 0.5f - cx) / fx, (static_cast<float>(row) + 0.5f - cy) / fy, 1.0f).normalized();
        lutex::SetPacketRay(lane, centre, direction, &packet);
      }
      rtcIntersect16(valid, scene, &context, &packet);
      for (int lane = 0; lane < 16; ++lane) {
        const int col = block_col * 4 + lane % 4, row = static_cast<int>(block_row) * 4 + lane / 4;
        if (valid[lane] && packet.hit.geomID[lane] != RTC_INVALID_GEOMETRY_ID) {
          (*depth)[static_cast<std::size_t>(row) * width + col] = packet.ray.tfar[lane];
        }
      }
    }
  });
  const double seconds = lutex::bench::SecondsSince(start);
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  return seconds;
}

}  // namespace

int main(int argc, char** argv) {
  lutex::bench::Options args(argc, argv, "raycast_benchmark [--width 4000] [--height 3000] [--cells 710] [--repeats 3] [--num-threads 0]");
  const int width = args.Int("--width", 4000);
  const int height = args.Int("--height", 3000);
  const int cells = args.Int("--cells", 710);
  const int repeats = args.Int("--repeats", 3);
  const int num_threads = lutex::ResolveNumThreads(args.Int("--num-threads", 0));
  args.CheckAllRead();

  const lutex::Mesh mesh = lutex::MakeHeightFieldMesh(
      [](double x, double y) { return 0.2 * std::sin(2.0 * x) * std::cos(1.5 * y); }, -4, 4, -3, 3, cells, cells);
  const lutex::Camera camera =
      lutex::Camera::Pinhole(1, static_cast<std::uint64_t>(width), static_cast<std::uint64_t>(height), 0.5 * width, 0.5 * width);
  const lutex::Rigid3d cam_from_world =
      lutex::CamFromWorldLookingAt(Eigen::Vector3d(0, 0, 3), Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, -1, 0));
  const double rays = static_cast<double>(width) * height;
  std::cout << "mesh: " << mesh.NumFaces() << " faces; camera " << width << "x" << height << "; " << num_threads
            << " threads; best of " << repeats << "\n";

  auto start = std::chrono::steady_clock::now();
  const lutex::RaycastScene scene(mesh);
  std::cout << "BVH build (lutex): " << lutex::bench::SecondsSince(start) << " s\n";
  start = std::chrono::steady_clock::now();
  const lutex::CameraRays camera_rays(camera, num_threads);
  std::cout << "ray table (once per camera): " << lutex::bench::SecondsSince(start) << " s\n";

  double lutex_best = 1e30, bare_best = 1e30;
  std::vector<float> bare_depth;
  lutex::GeometryMapsOptions options;
  options.num_threads = num_threads;
  for (int r = 0; r < repeats; ++r) {
    start = std::chrono::steady_clock::now();
    const lutex::GeometryMaps maps = scene.Render(camera_rays, cam_from_world, options);
    lutex_best = std::min(lutex_best, lutex::bench::SecondsSince(start));
    bare_best = std::min(bare_best, BareEmbreeSeconds(mesh, camera, cam_from_world, num_threads, &bare_depth));
  }
  std::cout << "lutex Render (depth + normal + face id): " << rays / lutex_best / 1e6 << " M rays/s (" << lutex_best
            << " s)\n"
            << "bare Embree rtcIntersect16 loop (depth only): " << rays / bare_best / 1e6 << " M rays/s (" << bare_best
            << " s)\n"
            << "ratio lutex / bare time: " << lutex_best / bare_best << "\n";
  return 0;
}
