#include "lib/raycast/raycast_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

#include "lib/raycast/embree_ray_packet.h"
#include "lib/util/parallel_for.h"

namespace lutex {
namespace {

// Packets of 16 rays cover 4x4 pixel blocks: coherent rays traverse the BVH together.
constexpr int kBlock = 4;

const char* EmbreeErrorName(RTCError error) {
  switch (error) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
  }
  return "unrecognised error";
}

}  // namespace

struct RaycastScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // world point that is (0, 0, 0) for Embree
  std::size_t num_faces = 0;
  std::mutex error_mutex;
  std::string first_error;

  // Embree calls this from its own threads; it must not throw.
  static void OnError(void* user, RTCError code, const char* message) {
    auto* impl = static_cast<Impl*>(user);
    std::lock_guard<std::mutex> lock(impl->error_mutex);
    if (impl->first_error.empty()) {
      impl->first_error = std::string(EmbreeErrorName(code)) + (message ? std::string(": ") + message : "");
    }
  }

  void ThrowIfError(const std::string& what) {
    std::lock_guard<std::mutex> lock(error_mutex);
    if (!first_error.empty()) throw std::runtime_error("Embree failed to " + what + ": " + first_error);
  }

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

RaycastScene::RaycastScene(const Mesh& mesh) : impl_(std::make_unique<Impl>()) {
  mesh.Check("mesh for ray casting");
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) {
    throw std::runtime_error(std::string("Embree failed to create a device: ") +
                             EmbreeErrorName(rtcGetDeviceError(nullptr)));
  }
  rtcSetDeviceErrorFunction(impl_->device, &Impl::OnError, impl_.get());

  impl_->origin = 0.5 * (mesh.BoundsMin() + mesh.BoundsMax());
  impl_->num_faces = mesh.faces.size();
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);

  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Embree allocates these buffers with the padding its SIMD loads need.
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
  auto* indices = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), mesh.faces.size()));
  if (!vertices || !indices) {
    rtcReleaseGeometry(geometry);
    impl_->ThrowIfError("allocate the mesh buffers");
    throw std::runtime_error("Embree failed to allocate the mesh buffers");
  }
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3f local = (mesh.vertices[i] - impl_->origin).cast<float>();
    std::copy(local.data(), local.data() + 3, vertices + 3 * i);
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    std::copy(mesh.faces[f].begin(), mesh.faces[f].end(), indices + 3 * f);
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl_->scene);
  impl_->ThrowIfError("build the ray-casting scene");
}

RaycastScene::~RaycastScene() = default;

std::size_t RaycastScene::NumFaces() const { return impl_->num_faces; }

RayHit RaycastScene::Intersect(const Eigen::Vector3d& origin_in_world,
                               const Eigen::Vector3d& direction_in_world) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayhit{};
  const Eigen::Vector3f origin = (origin_in_world - impl_->origin).cast<float>();
  const Eigen::Vector3f direction = direction_in_world.cast<float>();
  rayhit.ray.org_x = origin.x();
  rayhit.ray.org_y = origin.y();
  rayhit.ray.org_z = origin.z();
  rayhit.ray.dir_x = direction.x();
  rayhit.ray.dir_y = direction.y();
  rayhit.ray.dir_z = direction.z();
  rayhit.ray.tnear = 0.0f;
  rayhit.ray.tfar = std::numeric_limits<float>::infinity();
  rayhit.ray.mask = 0xFFFFFFFFu;
  rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rayhit);
  RayHit result;
  if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return result;
  result.hit = true;
  result.distance = rayhit.ray.tfar;
  result.face_id = static_cast<int>(rayhit.hit.primID);
  Eigen::Vector3d normal(rayhit.hit.Ng_x, rayhit.hit.Ng_y, rayhit.hit.Ng_z);
  normal.normalize();
  if (normal.dot(direction_in_world) > 0.0) normal = -normal;
  result.normal_in_world = normal;
  return result;
}

GeometryMaps RaycastScene::Render(const CameraRays& rays, const Rigid3d& cam_from_world,
                                  const GeometryMapsOptions& options) const {
  if (!cam_from_world.IsValid()) {
    throw std::invalid_argument("pose for ray casting is not finite or its quaternion is not unit");
  }
  const int width = rays.width();
  const int height = rays.height();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  GeometryMaps maps;
  maps.depth = cv::Mat(height, width, CV_32F, cv::Scalar(nan));
  if (options.normal) maps.normal = cv::Mat(height, width, CV_32FC3, cv::Scalar::all(nan));
  if (options.face_id) maps.face_id = cv::Mat(height, width, CV_32S, cv::Scalar(-1));
  if (options.barycentrics) maps.barycentrics = cv::Mat(height, width, CV_32FC2, cv::Scalar::all(nan));

  const Eigen::Matrix3f cam_from_world_rotation = cam_from_world.rotation.toRotationMatrix().cast<float>();
  const Eigen::Matrix3f world_from_cam_rotation = cam_from_world_rotation.transpose();
  const Eigen::Vector3f centre =
      (cam_from_world.TargetOriginInSource() - impl_->origin).cast<float>();
  const int block_rows = (height + kBlock - 1) / kBlock;
  const int block_cols = (width + kBlock - 1) / kBlock;

  ParallelFor(static_cast<std::size_t>(block_rows), options.num_threads, [&](std::size_t block_row) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    alignas(64) RTCRayHit16 packet;
    alignas(64) int valid[16];
    for (int block_col = 0; block_col < block_cols; ++block_col) {
      for (int lane = 0; lane < 16; ++lane) {
        const int col = block_col * kBlock + lane % kBlock;
        const int row = static_cast<int>(block_row) * kBlock + lane / kBlock;
        const bool inside = col < width && row < height;
        const Eigen::Vector3f direction_in_cam =
            inside ? rays.Direction(col, row) : Eigen::Vector3f::Constant(nan);
        valid[lane] = inside && direction_in_cam.allFinite() ? -1 : 0;
        const Eigen::Vector3f direction =
            valid[lane] ? Eigen::Vector3f(world_from_cam_rotation * direction_in_cam) : Eigen::Vector3f(0, 0, 1);
        SetPacketRay(lane, centre, direction, &packet);
      }
      rtcIntersect16(valid, impl_->scene, &context, &packet);
      for (int lane = 0; lane < 16; ++lane) {
        if (!valid[lane] || packet.hit.geomID[lane] == RTC_INVALID_GEOMETRY_ID) continue;
        const int col = block_col * kBlock + lane % kBlock;
        const int row = static_cast<int>(block_row) * kBlock + lane / kBlock;
        const Eigen::Vector3f& direction_in_cam = rays.Direction(col, row);
        maps.depth.at<float>(row, col) = packet.ray.tfar[lane] * direction_in_cam.z();
        if (options.normal) {
          Eigen::Vector3f normal_in_cam =
              cam_from_world_rotation *
              Eigen::Vector3f(packet.hit.Ng_x[lane], packet.hit.Ng_y[lane], packet.hit.Ng_z[lane]);
          normal_in_cam.normalize();
          if (normal_in_cam.dot(direction_in_cam) > 0.0f) normal_in_cam = -normal_in_cam;
          maps.normal.at<cv::Vec3f>(row, col) =
              cv::Vec3f(normal_in_cam.x(), normal_in_cam.y(), normal_in_cam.z());
        }
        if (options.face_id) maps.face_id.at<int>(row, col) = static_cast<int>(packet.hit.primID[lane]);
        if (options.barycentrics) {
          maps.barycentrics.at<cv::Vec2f>(row, col) = cv::Vec2f(packet.hit.u[lane], packet.hit.v[lane]);
        }
      }
    }
  });
  return maps;
}

}  // namespace lutex
