#include "lib/raycast/raycast_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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
  // The mesh in double precision relative to `origin`, for analytic plane intersections.
  std::vector<Eigen::Vector3d> local_vertices;
  std::vector<Mesh::Face> faces;
  std::vector<Eigen::Vector3f> vertex_normals;  // the mesh's, world frame; empty when it has none
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
  if (!vertices) {
    rtcReleaseGeometry(geometry);
    impl_->ThrowIfError("allocate the mesh buffers");
    throw std::runtime_error("Embree failed to allocate the mesh buffers");
  }
  // The index buffer is the scene's own copy of the faces, shared with Embree (index buffers need no
  // padding; it lives as long as the scene, which is released first).
  impl_->faces = mesh.faces;
  static_assert(sizeof(Mesh::Face) == 3 * sizeof(std::uint32_t), "faces are three packed indices");
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, impl_->faces.data(), 0,
                             sizeof(Mesh::Face), impl_->faces.size());
  impl_->vertex_normals = mesh.vertex_normals;
  impl_->local_vertices.reserve(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    impl_->local_vertices.push_back(mesh.vertices[i] - impl_->origin);
    const Eigen::Vector3f local = (mesh.vertices[i] - impl_->origin).cast<float>();
    std::copy(local.data(), local.data() + 3, vertices + 3 * i);
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
  result.b1 = rayhit.hit.u;
  result.b2 = rayhit.hit.v;
  Eigen::Vector3d normal(rayhit.hit.Ng_x, rayhit.hit.Ng_y, rayhit.hit.Ng_z);
  normal.normalize();
  if (normal.dot(direction_in_world) > 0.0) normal = -normal;
  result.normal_in_world = normal;
  return result;
}

namespace {

// What one ray found, before it is written into the maps.
struct PixelHit {
  float distance = 0.0f;  // along the unit ray
  int face = -1;
  float b1 = 0.0f, b2 = 0.0f;
  Eigen::Vector3f unit_normal_in_cam = Eigen::Vector3f::Zero();  // either orientation
};

// A triangle prepared for intersecting many rays of one camera pose, in the camera frame: the ray
// x = t d (d a unit direction) meets its plane at t = offset / (normal . d), at barycentrics
// (dual1 . (x - p0), dual2 . (x - p0)), dual1 and dual2 being the dual basis of the edges in the plane.
struct FacePlane {
  int face = -1;  // -1: degenerate (no area)
  Eigen::Vector3f p0, normal, dual1, dual2;  // normal: unit
  float offset = 0.0f;

  FacePlane() = default;
  // Vertices relative to the camera centre, in the camera frame (double: the edges of a small triangle far
  // from the mesh origin lose no precision before they are rounded).
  FacePlane(int face_id, const Eigen::Vector3d& v0_in_cam, const Eigen::Vector3d& v1_in_cam,
            const Eigen::Vector3d& v2_in_cam) {
    const Eigen::Vector3d e1 = v1_in_cam - v0_in_cam, e2 = v2_in_cam - v0_in_cam;
    const Eigen::Vector3d plane_normal = e1.cross(e2);
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const double determinant = d11 * d22 - d12 * d12;
    if (!(determinant > 0.0) || !(plane_normal.squaredNorm() > 0.0)) return;
    face = face_id;
    // Scaled to unit length so that float keeps its precision whatever the triangle's size.
    const Eigen::Vector3d unit = plane_normal.normalized();
    p0 = v0_in_cam.cast<float>();
    normal = unit.cast<float>();
    offset = static_cast<float>(unit.dot(v0_in_cam));
    dual1 = ((d22 * e1 - d12 * e2) / determinant).cast<float>();
    dual2 = ((d11 * e2 - d12 * e1) / determinant).cast<float>();
  }

  PixelHit Intersect(const Eigen::Vector3f& direction_in_cam) const {
    PixelHit hit;
    const float along = normal.dot(direction_in_cam);
    if (face < 0 || along == 0.0f) return hit;
    const float t = offset / along;
    const Eigen::Vector3f from_p0 = t * direction_in_cam - p0;
    hit.distance = t;
    hit.face = face;
    hit.b1 = dual1.dot(from_p0);
    hit.b2 = dual2.dot(from_p0);
    hit.unit_normal_in_cam = normal;
    return hit;
  }
};

// Casts up to 16 pixels of `rays` from `centre` (the camera centre relative to the scene's origin) as one
// packet, and calls write(col, row, hit) for each with what it hit (face -1: nothing).
template <typename WriteHit>
void CastPacket(RTCScene scene, const CameraRays& rays, const Eigen::Vector3f& centre,
                const Eigen::Matrix3f& world_from_cam_rotation, const Eigen::Matrix3f& cam_from_world_rotation,
                const std::array<std::pair<int, int>, 16>& pixels, int count, const WriteHit& write) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(64) RTCRayHit16 packet;
  alignas(64) int valid[16];
  for (int lane = 0; lane < 16; ++lane) {
    const bool used = lane < count;
    const Eigen::Vector3f direction_in_cam =
        used ? rays.Direction(pixels[lane].first, pixels[lane].second) : Eigen::Vector3f::Constant(nan);
    valid[lane] = used && direction_in_cam.allFinite() ? -1 : 0;
    const Eigen::Vector3f direction =
        valid[lane] ? Eigen::Vector3f(world_from_cam_rotation * direction_in_cam) : Eigen::Vector3f(0, 0, 1);
    SetPacketRay(lane, centre, direction, &packet);
  }
  rtcIntersect16(valid, scene, &context, &packet);
  for (int lane = 0; lane < count; ++lane) {
    PixelHit hit;
    if (valid[lane] && packet.hit.geomID[lane] != RTC_INVALID_GEOMETRY_ID) {
      hit.distance = packet.ray.tfar[lane];
      hit.face = static_cast<int>(packet.hit.primID[lane]);
      hit.b1 = packet.hit.u[lane];
      hit.b2 = packet.hit.v[lane];
      hit.unit_normal_in_cam =
          (cam_from_world_rotation * Eigen::Vector3f(packet.hit.Ng_x[lane], packet.hit.Ng_y[lane], packet.hit.Ng_z[lane]))
              .normalized();
    }
    write(pixels[lane].first, pixels[lane].second, hit);
  }
}

// Everything needed to fill the maps of one camera pose: the pose in float and double, the maps, and the
// scene's triangles relative to the camera. Rendering is two passes (see RaycastScene::Render): cast the
// samples, then fill the pixels between them from the triangles the samples hit, casting what cannot be
// filled.
class PoseRenderer {
 public:
  PoseRenderer(RTCScene scene, const Eigen::Vector3d& scene_origin, const std::vector<Eigen::Vector3d>& local_vertices,
               const std::vector<Mesh::Face>& faces, const std::vector<Eigen::Vector3f>& vertex_normals,
               const CameraRays& rays, const Rigid3d& cam_from_world, const GeometryMapsOptions& options,
               GeometryMaps* maps)
      : scene_(scene),
        local_vertices_(local_vertices),
        faces_(faces),
        vertex_normals_(vertex_normals),
        rays_(rays),
        options_(options),
        maps_(*maps),
        cam_from_world_rotation_(cam_from_world.rotation.toRotationMatrix().cast<float>()),
        world_from_cam_rotation_(cam_from_world_rotation_.transpose()),
        cam_from_world_rotation_d_(cam_from_world.rotation.toRotationMatrix()),
        centre_local_(cam_from_world.TargetOriginInSource() - scene_origin),
        centre_(centre_local_.cast<float>()) {
    const cv::Rect image(0, 0, rays.width(), rays.height());
    cv::Rect window = options.window.empty() ? image : (options.window & image);
    if (window.empty()) window = cv::Rect();
    window.width += window.x % 2;  // the corner to even coordinates, the far edges kept
    window.height += window.y % 2;
    window.x -= window.x % 2;
    window.y -= window.y % 2;
    begin_col_ = window.x;
    begin_row_ = window.y;
    end_col_ = window.x + window.width;
    end_row_ = window.y + window.height;
    AllocateMaps();
  }

  // True when the window has no pixel (nothing to cast).
  bool Empty() const { return end_col_ <= begin_col_ || end_row_ <= begin_row_; }

  // Pass 1: the sample pixels (every `step`-th column and row, and always the last one), cast in packets
  // of 4 x 4 samples.
  void CastSamples(int step) {
    for (int c = begin_col_; c < end_col_; c += step) sample_cols_.push_back(c);
    if (sample_cols_.back() != end_col_ - 1) sample_cols_.push_back(end_col_ - 1);
    for (int r = begin_row_; r < end_row_; r += step) sample_rows_.push_back(r);
    if (sample_rows_.back() != end_row_ - 1) sample_rows_.push_back(end_row_ - 1);
    const int block_rows = static_cast<int>((sample_rows_.size() + kBlock - 1) / kBlock);
    const int block_cols = static_cast<int>((sample_cols_.size() + kBlock - 1) / kBlock);
    ParallelFor(static_cast<std::size_t>(block_rows), options_.num_threads, [&](std::size_t block_row) {
      std::array<std::pair<int, int>, 16> pixels;
      for (int block_col = 0; block_col < block_cols; ++block_col) {
        int count = 0;
        for (int lane = 0; lane < 16; ++lane) {
          const std::size_t sc = static_cast<std::size_t>(block_col * kBlock + lane % kBlock);
          const std::size_t sr = block_row * kBlock + static_cast<std::size_t>(lane / kBlock);
          if (sc < sample_cols_.size() && sr < sample_rows_.size()) pixels[count++] = {sample_cols_[sc], sample_rows_[sr]};
        }
        Cast(pixels, count);
      }
    });
  }

  // Pass 2: every other pixel. Its enclosing samples (the pixel itself where it is one) were written in
  // pass 1 and are only read here, and each row writes only itself, so rows run in parallel.
  void FillBetweenSamples() {
    const std::vector<std::pair<int, int>> cols_around = Enclosing(sample_cols_, begin_col_, end_col_);
    const std::vector<std::pair<int, int>> rows_around = Enclosing(sample_rows_, begin_row_, end_row_);
    ParallelFor(rows_around.size(), options_.num_threads, [&](std::size_t row_index) {
      FillRow(begin_row_ + static_cast<int>(row_index), rows_around[row_index], cols_around);
    });
  }

 private:
  // Every pixel is written exactly once (a hit or a miss), so the maps need no initial values.
  void AllocateMaps() {
    const int width = end_col_ - begin_col_, height = end_row_ - begin_row_;
    maps_.origin = cv::Point(begin_col_, begin_row_);
    maps_.depth.create(height, width, CV_32F);
    maps_.face_id.create(height, width, CV_32S);
    if (options_.normal) {
      maps_.normal.create(height, width, CV_32FC3);
    } else {
      maps_.normal.release();
    }
    if (options_.barycentrics) {
      maps_.barycentrics.create(height, width, CV_32FC2);
    } else {
      maps_.barycentrics.release();
    }
  }

  // Pixel (col, row) of the image.
  void Write(int col, int row, const PixelHit& hit) const {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Eigen::Vector3f& direction_in_cam = rays_.Direction(col, row);
    col -= begin_col_;
    row -= begin_row_;
    maps_.face_id.at<int>(row, col) = hit.face;
    if (hit.face < 0) {
      maps_.depth.at<float>(row, col) = nan;
      if (options_.normal) maps_.normal.at<cv::Vec3f>(row, col) = cv::Vec3f(nan, nan, nan);
      if (options_.barycentrics) maps_.barycentrics.at<cv::Vec2f>(row, col) = cv::Vec2f(nan, nan);
      return;
    }
    maps_.depth.at<float>(row, col) = hit.distance * direction_in_cam.z();
    if (options_.normal) {
      Eigen::Vector3f facing = hit.unit_normal_in_cam;
      if (facing.dot(direction_in_cam) > 0.0f) facing = -facing;
      // The smooth normal on the side the face is seen from (near a silhouette it may face away from the
      // ray itself, as the surface it stands for does).
      Eigen::Vector3f normal_in_cam = ShadingNormal(hit);
      if (normal_in_cam.dot(facing) < 0.0f) normal_in_cam = -normal_in_cam;
      maps_.normal.at<cv::Vec3f>(row, col) = cv::Vec3f(normal_in_cam.x(), normal_in_cam.y(), normal_in_cam.z());
    }
    if (options_.barycentrics) maps_.barycentrics.at<cv::Vec2f>(row, col) = cv::Vec2f(hit.b1, hit.b2);
  }

  // The mesh's vertex normals interpolated at the hit (photogrammetry meshes carry smooth normals; the
  // facets' own normals would shade a curved surface in facets), else the face's normal; either
  // orientation.
  Eigen::Vector3f ShadingNormal(const PixelHit& hit) const {
    if (vertex_normals_.empty()) return hit.unit_normal_in_cam;
    const Mesh::Face& corners = faces_[static_cast<std::size_t>(hit.face)];
    const Eigen::Vector3f in_world = (1.0f - hit.b1 - hit.b2) * vertex_normals_[corners[0]] +
                                     hit.b1 * vertex_normals_[corners[1]] + hit.b2 * vertex_normals_[corners[2]];
    const float length = in_world.norm();
    if (!(length > 1e-6f) || !std::isfinite(length)) return hit.unit_normal_in_cam;  // opposed corner normals
    return cam_from_world_rotation_ * (in_world / length);
  }

  // Casts up to 16 pixels as one packet and writes what they hit.
  void Cast(const std::array<std::pair<int, int>, 16>& pixels, int count) const {
    CastPacket(scene_, rays_, centre_, world_from_cam_rotation_, cam_from_world_rotation_, pixels, count,
               [this](int col, int row, const PixelHit& hit) { Write(col, row, hit); });
  }

  // The triangle `face` prepared for this pose.
  FacePlane Prepare(int face) const {
    const Mesh::Face& corners = faces_[static_cast<std::size_t>(face)];
    const auto in_cam = [&](std::uint32_t vertex) {
      return Eigen::Vector3d(cam_from_world_rotation_d_ * (local_vertices_[vertex] - centre_local_));
    };
    return FacePlane(face, in_cam(corners[0]), in_cam(corners[1]), in_cam(corners[2]));
  }

  bool ShareVertex(int face_a, int face_b) const {
    const Mesh::Face& a = faces_[static_cast<std::size_t>(face_a)];
    const Mesh::Face& b = faces_[static_cast<std::size_t>(face_b)];
    return std::any_of(a.begin(), a.end(), [&](auto vertex) { return std::find(b.begin(), b.end(), vertex) != b.end(); });
  }

  // The hit of a pixel between four samples, from the faces the samples hit, without casting. When all
  // four hit one triangle: its plane (the pixel's ray lies between theirs, so it meets that triangle too).
  // When they hit up to four triangles that pairwise share a vertex (one piece of surface across an edge
  // or around a vertex): the nearest of them whose triangle the pixel's ray meets. Otherwise no hit
  // (face -1), and the pixel is cast. `plane_of(face)` gives the prepared FacePlane of a face.
  template <typename PlaneOf>
  PixelHit HitAmongCornerFaces(const std::array<int, 4>& corners, const Eigen::Vector3f& direction_in_cam,
                               PlaneOf& plane_of) const {
    if (std::any_of(corners.begin(), corners.end(), [](int face) { return face < 0; })) return PixelHit{};
    if (std::all_of(corners.begin(), corners.end(), [&](int face) { return face == corners[0]; })) {
      return plane_of(corners[0]).Intersect(direction_in_cam);
    }
    std::array<int, 4> distinct{};
    int count = 0;
    for (const int face : corners) {
      if (std::find(distinct.begin(), distinct.begin() + count, face) == distinct.begin() + count) distinct[count++] = face;
    }
    for (int i = 0; i < count; ++i) {
      for (int j = i + 1; j < count; ++j) {
        if (!ShareVertex(distinct[i], distinct[j])) return PixelHit{};
      }
    }
    PixelHit nearest;
    for (int i = 0; i < count; ++i) {
      const PixelHit hit = plane_of(distinct[i]).Intersect(direction_in_cam);
      const bool inside = hit.face >= 0 && hit.distance > 0.0f && hit.b1 >= 0.0f && hit.b2 >= 0.0f && hit.b1 + hit.b2 <= 1.0f;
      if (inside && (nearest.face < 0 || hit.distance < nearest.distance)) nearest = hit;
    }
    return nearest;
  }

  // For every pixel begin..end-1 (at index i - begin) the samples around it: (i, i) where i is a sample.
  static std::vector<std::pair<int, int>> Enclosing(const std::vector<int>& samples, int begin, int end) {
    std::vector<std::pair<int, int>> result(static_cast<std::size_t>(end - begin));
    std::size_t s = 0;
    for (int i = begin; i < end; ++i) {
      while (s + 1 < samples.size() && samples[s + 1] <= i) ++s;
      result[static_cast<std::size_t>(i - begin)] =
          samples[s] == i ? std::make_pair(i, i) : std::make_pair(samples[s], samples[s + 1]);
    }
    return result;
  }

  // Pass 2 on one row: fills what the corner faces give, casts the rest in packets of 16.
  void FillRow(int row, std::pair<int, int> rows_around, const std::vector<std::pair<int, int>>& cols_around) const {
    const auto [row0, row1] = rows_around;
    std::array<std::pair<int, int>, 16> pending;
    int count = 0;
    // The triangles this row met last, prepared (neighbouring pixels meet the same few), found by their
    // ids (kept apart: scanning the planes themselves would touch a cache line each).
    std::array<FacePlane, 8> recent;
    std::array<int, 8> recent_faces;
    recent_faces.fill(-1);
    std::size_t next_slot = 0;
    const auto plane_of = [&](int face) -> const FacePlane& {
      for (std::size_t slot = 0; slot < recent_faces.size(); ++slot) {
        if (recent_faces[slot] == face) return recent[slot];
      }
      const std::size_t slot = next_slot++ % recent.size();
      recent[slot] = Prepare(face);
      recent_faces[slot] = face;
      return recent[slot];
    };
    const cv::Mat& faces = maps_.face_id;
    const auto face_at = [&](int r, int c) { return faces.at<int>(r - begin_row_, c - begin_col_); };
    for (int col = begin_col_; col < end_col_; ++col) {
      const auto [col0, col1] = cols_around[static_cast<std::size_t>(col - begin_col_)];
      if (row0 == row && row1 == row && col0 == col && col1 == col) continue;  // a sample
      const std::array<int, 4> corners = {face_at(row0, col0), face_at(row0, col1), face_at(row1, col0),
                                          face_at(row1, col1)};
      const PixelHit hit = HitAmongCornerFaces(corners, rays_.Direction(col, row), plane_of);
      if (hit.face >= 0) {
        Write(col, row, hit);
        continue;
      }
      pending[count++] = {col, row};
      if (count == 16) {
        Cast(pending, count);
        count = 0;
      }
    }
    if (count > 0) Cast(pending, count);
  }

  RTCScene scene_;
  const std::vector<Eigen::Vector3d>& local_vertices_;
  const std::vector<Mesh::Face>& faces_;
  const std::vector<Eigen::Vector3f>& vertex_normals_;
  const CameraRays& rays_;
  const GeometryMapsOptions& options_;
  GeometryMaps& maps_;
  const Eigen::Matrix3f cam_from_world_rotation_;
  const Eigen::Matrix3f world_from_cam_rotation_;
  const Eigen::Matrix3d cam_from_world_rotation_d_;
  const Eigen::Vector3d centre_local_;  // the camera centre relative to the scene's origin
  const Eigen::Vector3f centre_;
  // The window rendered, in image pixels: [begin, end).
  int begin_col_ = 0, begin_row_ = 0, end_col_ = 0, end_row_ = 0;
  std::vector<int> sample_cols_, sample_rows_;
};

}  // namespace

GeometryMaps RaycastScene::Render(const CameraRays& rays, const Rigid3d& cam_from_world,
                                  const GeometryMapsOptions& options) const {
  GeometryMaps maps;
  Render(rays, cam_from_world, options, &maps);
  return maps;
}

void RaycastScene::Render(const CameraRays& rays, const Rigid3d& cam_from_world, const GeometryMapsOptions& options,
                          GeometryMaps* output) const {
  if (!cam_from_world.IsValid()) {
    throw std::invalid_argument("pose for ray casting is not finite or its quaternion is not unit");
  }
  PoseRenderer renderer(impl_->scene, impl_->origin, impl_->local_vertices, impl_->faces, impl_->vertex_normals,
                        rays, cam_from_world, options, output);
  if (renderer.Empty()) return;
  renderer.CastSamples(options.adaptive ? 2 : 1);
  if (options.adaptive) renderer.FillBetweenSamples();
}

void RaycastScene::CastDepths(const CameraRays& rays, const Rigid3d& cam_from_world, const std::vector<cv::Point>& pixels,
                              std::vector<float>* depths) const {
  if (!cam_from_world.IsValid()) {
    throw std::invalid_argument("pose for ray casting is not finite or its quaternion is not unit");
  }
  const Eigen::Matrix3f cam_from_world_rotation = cam_from_world.rotation.toRotationMatrix().cast<float>();
  const Eigen::Matrix3f world_from_cam_rotation = cam_from_world_rotation.transpose();
  const Eigen::Vector3f centre = (cam_from_world.TargetOriginInSource() - impl_->origin).cast<float>();
  depths->assign(pixels.size(), std::numeric_limits<float>::quiet_NaN());
  std::array<std::pair<int, int>, 16> packet;
  std::array<std::size_t, 16> index_of_lane;
  int count = 0;
  const auto cast = [&] {
    int lane = 0;
    CastPacket(impl_->scene, rays, centre, world_from_cam_rotation, cam_from_world_rotation, packet, count,
               [&](int col, int row, const PixelHit& hit) {
                 if (hit.face >= 0) (*depths)[index_of_lane[lane]] = hit.distance * rays.Direction(col, row).z();
                 ++lane;
               });
    count = 0;
  };
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const cv::Point& pixel = pixels[i];
    if (pixel.x < 0 || pixel.y < 0 || pixel.x >= rays.width() || pixel.y >= rays.height()) continue;
    index_of_lane[count] = i;
    packet[count++] = {pixel.x, pixel.y};
    if (count == 16) cast();
  }
  if (count > 0) cast();
}

}  // namespace lutex
