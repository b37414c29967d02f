#include "colmap_integration/io/sparse_model_text.h"

#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include "lib/util/file_streams.h"

namespace lutex {
namespace {

// Reads lines, skipping comments and blank lines, and knows its line number for errors.
class LineReader {
 public:
  explicit LineReader(std::istream& stream) : stream_(stream) {}

  // Next line that is neither blank nor a comment; false at the end.
  bool NextDataLine(std::string* line) {
    while (NextLine(line)) {
      const auto first = line->find_first_not_of(" \t\r");
      if (first != std::string::npos && (*line)[first] != '#') return true;
    }
    return false;
  }
  // Next line whatever it holds (the 2-D point line of images.txt may be empty).
  bool NextLine(std::string* line) {
    if (!std::getline(stream_, *line)) return false;
    ++line_number_;
    if (!line->empty() && line->back() == '\r') line->pop_back();
    return true;
  }
  std::runtime_error Error(const std::string& problem) const {
    return std::runtime_error("line " + std::to_string(line_number_) + ": " + problem);
  }

 private:
  std::istream& stream_;
  int line_number_ = 0;
};

template <typename T>
T Parse(std::istringstream& fields, const LineReader& reader, const char* what) {
  T value;
  if (!(fields >> value)) throw reader.Error(std::string("expected ") + what);
  return value;
}

// COLMAP writes -1 for "no 3-D point".
std::uint64_t ParsePoint3DId(std::istringstream& fields, const LineReader& reader) {
  const auto value = Parse<long long>(fields, reader, "a 3-D point id");
  return value < 0 ? kInvalidPoint3DId : static_cast<std::uint64_t>(value);
}

void ExpectEnd(std::istringstream& fields, const LineReader& reader, const char* what) {
  std::string extra;
  if (fields >> extra) throw reader.Error(std::string("unexpected '") + extra + "' after " + what);
}

void WriteFullPrecision(std::ostream& stream) { stream << std::setprecision(17); }

}  // namespace

std::map<std::uint32_t, Camera> ReadCamerasText(std::istream& stream) {
  std::map<std::uint32_t, Camera> cameras;
  LineReader reader(stream);
  std::string line;
  while (reader.NextDataLine(&line)) {
    std::istringstream fields(line);
    Camera camera;
    camera.camera_id = Parse<std::uint32_t>(fields, reader, "a camera id");
    const auto model_name = Parse<std::string>(fields, reader, "a camera model name");
    try {
      camera.model_id = CameraModelIdFromName(model_name);
    } catch (const std::invalid_argument& error) {
      throw reader.Error(std::string("camera ") + std::to_string(camera.camera_id) + ": " + error.what());
    }
    camera.width = Parse<std::uint64_t>(fields, reader, "the image width");
    camera.height = Parse<std::uint64_t>(fields, reader, "the image height");
    double param;
    while (fields >> param) camera.params.push_back(param);
    if (!fields.eof()) throw reader.Error("a camera parameter is not a number");
    if (camera.params.size() != CameraModelNumParams(camera.model_id)) {
      throw reader.Error("camera " + std::to_string(camera.camera_id) + " has model " + model_name +
                         ", which takes " + std::to_string(CameraModelNumParams(camera.model_id)) +
                         " parameters (" + CameraModelParamsInfo(camera.model_id) + "), but " +
                         std::to_string(camera.params.size()) + " are given");
    }
    if (!cameras.emplace(camera.camera_id, camera).second) {
      throw reader.Error("camera " + std::to_string(camera.camera_id) + " is defined twice");
    }
  }
  return cameras;
}

std::map<std::uint32_t, Image> ReadImagesText(std::istream& stream) {
  std::map<std::uint32_t, Image> images;
  LineReader reader(stream);
  std::string line;
  while (reader.NextDataLine(&line)) {
    std::istringstream fields(line);
    Image image;
    image.image_id = Parse<std::uint32_t>(fields, reader, "an image id");
    double q[4], t[3];
    for (double& value : q) value = Parse<double>(fields, reader, "the quaternion QW QX QY QZ");
    for (double& value : t) value = Parse<double>(fields, reader, "the translation TX TY TZ");
    image.cam_from_world = Rigid3d(Eigen::Quaterniond(q[0], q[1], q[2], q[3]), Eigen::Vector3d(t[0], t[1], t[2]));
    image.camera_id = Parse<std::uint32_t>(fields, reader, "a camera id");
    image.name = Parse<std::string>(fields, reader, "an image name");
    ExpectEnd(fields, reader, "the image name");
    if (!reader.NextLine(&line)) throw reader.Error("image " + std::to_string(image.image_id) + " lacks its 2-D point line");
    std::istringstream points(line);
    double x;
    while (points >> x) {
      Point2D point;
      point.xy.x() = x;
      point.xy.y() = Parse<double>(points, reader, "the y of a 2-D point");
      point.point3D_id = ParsePoint3DId(points, reader);
      image.points2D.push_back(point);
    }
    if (!points.eof()) throw reader.Error("a 2-D point coordinate is not a number");
    if (!images.emplace(image.image_id, image).second) {
      throw reader.Error("image " + std::to_string(image.image_id) + " is defined twice");
    }
  }
  return images;
}

std::map<std::uint64_t, Point3D> ReadPoints3DText(std::istream& stream) {
  std::map<std::uint64_t, Point3D> points3D;
  LineReader reader(stream);
  std::string line;
  while (reader.NextDataLine(&line)) {
    std::istringstream fields(line);
    Point3D point;
    point.point3D_id = Parse<std::uint64_t>(fields, reader, "a 3-D point id");
    for (int k = 0; k < 3; ++k) point.xyz[k] = Parse<double>(fields, reader, "the position X Y Z");
    for (int k = 0; k < 3; ++k) {
      const int channel = Parse<int>(fields, reader, "the colour R G B");
      if (channel < 0 || channel > 255) throw reader.Error("a colour channel is outside 0-255");
      point.color[k] = static_cast<std::uint8_t>(channel);
    }
    point.error = Parse<double>(fields, reader, "the reprojection error");
    std::uint32_t image_id;
    while (fields >> image_id) {
      TrackElement element;
      element.image_id = image_id;
      element.point2D_idx = Parse<std::uint32_t>(fields, reader, "a 2-D point index of the track");
      point.track.push_back(element);
    }
    if (!fields.eof()) throw reader.Error("a track entry is not a number");
    if (!points3D.emplace(point.point3D_id, point).second) {
      throw reader.Error("3-D point " + std::to_string(point.point3D_id) + " is defined twice");
    }
  }
  return points3D;
}

std::map<std::uint32_t, Camera> ReadCamerasText(const std::filesystem::path& path) {
  return ParseFile(path, std::ios::in, [](std::istream& s) { return ReadCamerasText(s); });
}
std::map<std::uint32_t, Image> ReadImagesText(const std::filesystem::path& path) {
  return ParseFile(path, std::ios::in, [](std::istream& s) { return ReadImagesText(s); });
}
std::map<std::uint64_t, Point3D> ReadPoints3DText(const std::filesystem::path& path) {
  return ParseFile(path, std::ios::in, [](std::istream& s) { return ReadPoints3DText(s); });
}

void WriteCamerasText(const std::map<std::uint32_t, Camera>& cameras, std::ostream& stream) {
  WriteFullPrecision(stream);
  stream << "# Camera list with one line of data per camera:\n"
            "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
            "# Number of cameras: "
         << cameras.size() << "\n";
  for (const auto& [camera_id, camera] : cameras) {
    stream << camera_id << " " << CameraModelName(camera.model_id) << " " << camera.width << " " << camera.height;
    for (double param : camera.params) stream << " " << param;
    stream << "\n";
  }
}

void WriteImagesText(const std::map<std::uint32_t, Image>& images, std::ostream& stream) {
  WriteFullPrecision(stream);
  std::size_t num_points2D = 0;
  for (const auto& entry : images) num_points2D += entry.second.points2D.size();
  stream << "# Image list with two lines of data per image:\n"
            "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
            "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
            "# Number of images: "
         << images.size() << ", mean observations per image: "
         << (images.empty() ? 0.0 : static_cast<double>(num_points2D) / static_cast<double>(images.size()))
         << "\n";
  for (const auto& [image_id, image] : images) {
    const Eigen::Quaterniond& q = image.cam_from_world.rotation;
    const Eigen::Vector3d& t = image.cam_from_world.translation;
    stream << image_id << " " << q.w() << " " << q.x() << " " << q.y() << " " << q.z() << " " << t.x() << " "
           << t.y() << " " << t.z() << " " << image.camera_id << " " << image.name << "\n";
    bool first = true;
    for (const Point2D& point : image.points2D) {
      stream << (first ? "" : " ") << point.xy.x() << " " << point.xy.y() << " ";
      if (point.point3D_id == kInvalidPoint3DId) {
        stream << -1;
      } else {
        stream << point.point3D_id;
      }
      first = false;
    }
    stream << "\n";
  }
}

void WritePoints3DText(const std::map<std::uint64_t, Point3D>& points3D, std::ostream& stream) {
  WriteFullPrecision(stream);
  std::size_t track_total = 0;
  for (const auto& entry : points3D) track_total += entry.second.track.size();
  stream << "# 3D point list with one line of data per point:\n"
            "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
            "# Number of points: "
         << points3D.size() << ", mean track length: "
         << (points3D.empty() ? 0.0 : static_cast<double>(track_total) / static_cast<double>(points3D.size()))
         << "\n";
  for (const auto& [point3D_id, point] : points3D) {
    stream << point3D_id << " " << point.xyz.x() << " " << point.xyz.y() << " " << point.xyz.z() << " "
           << int(point.color[0]) << " " << int(point.color[1]) << " " << int(point.color[2]) << " " << point.error;
    for (const TrackElement& element : point.track) stream << " " << element.image_id << " " << element.point2D_idx;
    stream << "\n";
  }
}

}  // namespace lutex
