#include "colmap_integration/io/sparse_model_binary.h"

#include <string>

#include "lib/util/binary_io.h"
#include "lib/util/file_streams.h"

namespace lutex {
namespace {

// A corrupt count must not make us reserve gigabytes before the read fails.
constexpr std::uint64_t kMaxReserve = 1u << 16;

std::string Which(const char* kind, std::uint64_t id) { return std::string(kind) + " " + std::to_string(id); }

// COLMAP's files end with their last record: bytes after it mean the count is wrong or the file is damaged.
void ExpectEnd(std::istream& stream, std::uint64_t count, const char* records) {
  if (stream.peek() == std::istream::traits_type::eof()) return;
  throw std::runtime_error("data after the last of the " + std::to_string(count) + " " + records +
                           " the file declares (a wrong count, or a damaged file)");
}

}  // namespace

std::map<std::uint32_t, Camera> ReadCamerasBinary(std::istream& stream) {
  std::map<std::uint32_t, Camera> cameras;
  const auto count = ReadBinary<std::uint64_t>(stream, "the camera count");
  for (std::uint64_t i = 0; i < count; ++i) {
    Camera camera;
    camera.camera_id = ReadBinary<std::uint32_t>(stream, "a camera id");
    const std::string which = Which("camera", camera.camera_id);
    const auto model_id = ReadBinary<std::int32_t>(stream, (which + " (model id)").c_str());
    if (!IsKnownCameraModelId(model_id)) {
      throw std::runtime_error(which + " has unknown camera model id " + std::to_string(model_id) +
                               " (lutex knows ids 0-" + std::to_string(kNumCameraModels - 1) + ")");
    }
    camera.model_id = static_cast<CameraModelId>(model_id);
    camera.width = ReadBinary<std::uint64_t>(stream, (which + " (width)").c_str());
    camera.height = ReadBinary<std::uint64_t>(stream, (which + " (height)").c_str());
    camera.params.resize(CameraModelNumParams(camera.model_id));
    for (double& param : camera.params) param = ReadBinary<double>(stream, (which + " (params)").c_str());
    if (!cameras.emplace(camera.camera_id, camera).second) throw std::runtime_error(which + " is defined twice");
  }
  ExpectEnd(stream, count, "cameras");
  return cameras;
}

std::map<std::uint32_t, Image> ReadImagesBinary(std::istream& stream) {
  std::map<std::uint32_t, Image> images;
  const auto count = ReadBinary<std::uint64_t>(stream, "the image count");
  for (std::uint64_t i = 0; i < count; ++i) {
    Image image;
    image.image_id = ReadBinary<std::uint32_t>(stream, "an image id");
    const std::string which = Which("image", image.image_id);
    const char* pose = "an image pose";
    const double qw = ReadBinary<double>(stream, pose), qx = ReadBinary<double>(stream, pose);
    const double qy = ReadBinary<double>(stream, pose), qz = ReadBinary<double>(stream, pose);
    const double tx = ReadBinary<double>(stream, pose), ty = ReadBinary<double>(stream, pose);
    const double tz = ReadBinary<double>(stream, pose);
    image.cam_from_world = Rigid3d(Eigen::Quaterniond(qw, qx, qy, qz), Eigen::Vector3d(tx, ty, tz));
    image.camera_id = ReadBinary<std::uint32_t>(stream, (which + " (camera id)").c_str());
    for (char c = ReadBinary<char>(stream, (which + " (name)").c_str()); c != '\0';
         c = ReadBinary<char>(stream, (which + " (name)").c_str())) {
      image.name.push_back(c);
    }
    const auto num_points2D = ReadBinary<std::uint64_t>(stream, (which + " (2-D point count)").c_str());
    image.points2D.reserve(std::min(num_points2D, kMaxReserve));
    for (std::uint64_t j = 0; j < num_points2D; ++j) {
      Point2D point;
      point.xy.x() = ReadBinary<double>(stream, (which + " (2-D points)").c_str());
      point.xy.y() = ReadBinary<double>(stream, (which + " (2-D points)").c_str());
      point.point3D_id = ReadBinary<std::uint64_t>(stream, (which + " (2-D points)").c_str());
      image.points2D.push_back(point);
    }
    if (!images.emplace(image.image_id, std::move(image)).second) throw std::runtime_error(which + " is defined twice");
  }
  ExpectEnd(stream, count, "images");
  return images;
}

std::map<std::uint64_t, Point3D> ReadPoints3DBinary(std::istream& stream) {
  std::map<std::uint64_t, Point3D> points3D;
  const auto count = ReadBinary<std::uint64_t>(stream, "the 3-D point count");
  for (std::uint64_t i = 0; i < count; ++i) {
    Point3D point;
    point.point3D_id = ReadBinary<std::uint64_t>(stream, "a 3-D point id");
    const std::string which = Which("3-D point", point.point3D_id);
    for (int k = 0; k < 3; ++k) point.xyz[k] = ReadBinary<double>(stream, (which + " (position)").c_str());
    for (int k = 0; k < 3; ++k) point.color[k] = ReadBinary<std::uint8_t>(stream, (which + " (colour)").c_str());
    point.error = ReadBinary<double>(stream, (which + " (error)").c_str());
    const auto track_length = ReadBinary<std::uint64_t>(stream, (which + " (track length)").c_str());
    point.track.reserve(std::min(track_length, kMaxReserve));
    for (std::uint64_t j = 0; j < track_length; ++j) {
      TrackElement element;
      element.image_id = ReadBinary<std::uint32_t>(stream, (which + " (track)").c_str());
      element.point2D_idx = ReadBinary<std::uint32_t>(stream, (which + " (track)").c_str());
      point.track.push_back(element);
    }
    if (!points3D.emplace(point.point3D_id, std::move(point)).second) {
      throw std::runtime_error(which + " is defined twice");
    }
  }
  ExpectEnd(stream, count, "3-D points");
  return points3D;
}

std::map<std::uint32_t, Camera> ReadCamerasBinary(const std::filesystem::path& path) {
  return ParseFile(path, std::ios::binary, [](std::istream& s) { return ReadCamerasBinary(s); });
}
std::map<std::uint32_t, Image> ReadImagesBinary(const std::filesystem::path& path) {
  return ParseFile(path, std::ios::binary, [](std::istream& s) { return ReadImagesBinary(s); });
}
std::map<std::uint64_t, Point3D> ReadPoints3DBinary(const std::filesystem::path& path) {
  return ParseFile(path, std::ios::binary, [](std::istream& s) { return ReadPoints3DBinary(s); });
}

void WriteCamerasBinary(const std::map<std::uint32_t, Camera>& cameras, std::ostream& stream) {
  WriteBinary<std::uint64_t>(stream, cameras.size());
  for (const auto& [camera_id, camera] : cameras) {
    WriteBinary<std::uint32_t>(stream, camera_id);
    WriteBinary<std::int32_t>(stream, static_cast<std::int32_t>(camera.model_id));
    WriteBinary<std::uint64_t>(stream, camera.width);
    WriteBinary<std::uint64_t>(stream, camera.height);
    for (double param : camera.params) WriteBinary<double>(stream, param);
  }
}

void WriteImagesBinary(const std::map<std::uint32_t, Image>& images, std::ostream& stream) {
  WriteBinary<std::uint64_t>(stream, images.size());
  for (const auto& [image_id, image] : images) {
    WriteBinary<std::uint32_t>(stream, image_id);
    const Eigen::Quaterniond& q = image.cam_from_world.rotation;
    for (double value : {q.w(), q.x(), q.y(), q.z()}) WriteBinary<double>(stream, value);
    for (int k = 0; k < 3; ++k) WriteBinary<double>(stream, image.cam_from_world.translation[k]);
    WriteBinary<std::uint32_t>(stream, image.camera_id);
    stream.write(image.name.c_str(), static_cast<std::streamsize>(image.name.size() + 1));
    WriteBinary<std::uint64_t>(stream, image.points2D.size());
    for (const Point2D& point : image.points2D) {
      WriteBinary<double>(stream, point.xy.x());
      WriteBinary<double>(stream, point.xy.y());
      WriteBinary<std::uint64_t>(stream, point.point3D_id);
    }
  }
}

void WritePoints3DBinary(const std::map<std::uint64_t, Point3D>& points3D, std::ostream& stream) {
  WriteBinary<std::uint64_t>(stream, points3D.size());
  for (const auto& [point3D_id, point] : points3D) {
    WriteBinary<std::uint64_t>(stream, point3D_id);
    for (int k = 0; k < 3; ++k) WriteBinary<double>(stream, point.xyz[k]);
    for (int k = 0; k < 3; ++k) WriteBinary<std::uint8_t>(stream, point.color[k]);
    WriteBinary<double>(stream, point.error);
    WriteBinary<std::uint64_t>(stream, point.track.size());
    for (const TrackElement& element : point.track) {
      WriteBinary<std::uint32_t>(stream, element.image_id);
      WriteBinary<std::uint32_t>(stream, element.point2D_idx);
    }
  }
}

}  // namespace lutex
