#include "lib/calibration/targets.h"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "lib/calibration/albedo_json.h"
#include "lib/util/logging.h"
#include "lib/util/json_fields.h"

namespace lutex {
namespace {

Eigen::Vector3d PolygonNormal(const std::vector<Eigen::Vector3d>& corners) {
  // Newell's method: robust for any simple polygon.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < corners.size(); ++i) normal += corners[i].cross(corners[(i + 1) % corners.size()]);
  return normal;
}

}  // namespace

bool Target::Contains(const Eigen::Vector3d& point_in_world, double tolerance) const {
  const Eigen::Vector3d normal = PolygonNormal(corners_world).normalized();
  if (std::abs(normal.dot(point_in_world - corners_world[0])) > tolerance) return false;
  // Inside if the point is on the same side of every edge (convex or not: count crossings in the plane).
  const Eigen::Vector3d axis_u = (corners_world[1] - corners_world[0]).normalized();
  const Eigen::Vector3d axis_v = normal.cross(axis_u);
  const auto planar = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector2d((p - corners_world[0]).dot(axis_u), (p - corners_world[0]).dot(axis_v));
  };
  const Eigen::Vector2d q = planar(point_in_world);
  bool inside = false;
  for (std::size_t i = 0, j = corners_world.size() - 1; i < corners_world.size(); j = i++) {
    const Eigen::Vector2d a = planar(corners_world[i]), b = planar(corners_world[j]);
    if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

std::vector<Target> ReadTargets(const std::filesystem::path& path) {
  std::ifstream stream(path);
  if (!stream) throw std::runtime_error(path.string() + ": no such targets file");
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(stream);
  } catch (const nlohmann::json::exception& error) {
    throw std::runtime_error(path.string() + ": " + JsonErrorText(error));
  }
  if (!root.contains("targets") || !root["targets"].is_array() || root["targets"].empty()) {
    throw std::runtime_error(path.string() + ": needs a non-empty \"targets\" array");
  }
  std::vector<Target> targets;
  for (std::size_t t = 0; t < root["targets"].size(); ++t) {
    const nlohmann::json& entry = root["targets"][t];
    Target target;
    // The name (a string), else the id as written, else the position: never an exception of the JSON library.
    if (entry.contains("name") && entry["name"].is_string()) {
      target.name = entry["name"].get<std::string>();
    } else {
      target.name = entry.contains("id") ? entry["id"].dump() : "target " + std::to_string(t);
    }
    const std::string where = path.string() + ": target " + target.name;
    if (!entry.contains("corners_world")) {
      LogWarning() << where << " has no corners_world (not a planar target); skipped";
      continue;
    }
    try {
      target.albedo = ReadAlbedo(entry, "albedo");
      for (const auto& corner : entry.at("corners_world")) {
        target.corners_world.emplace_back(corner.at(0).get<double>(), corner.at(1).get<double>(), corner.at(2).get<double>());
      }
    } catch (const nlohmann::json::exception& error) {
      throw std::runtime_error(where + ": " + JsonErrorText(error));
    } catch (const std::runtime_error& error) {
      throw std::runtime_error(where + ": " + error.what());
    }
    if (target.corners_world.size() < 3 || PolygonNormal(target.corners_world).norm() < 1e-9) {
      throw std::runtime_error(where + ": corners_world must be at least 3 corners spanning an area");
    }
    const Eigen::Vector3d normal = PolygonNormal(target.corners_world).normalized();
    for (const Eigen::Vector3d& corner : target.corners_world) {
      if (std::abs(normal.dot(corner - target.corners_world[0])) > 1e-3) {
        throw std::runtime_error(where + ": corners_world are not coplanar (to 1 mm)");
      }
    }
    targets.push_back(target);
  }
  if (targets.empty()) throw std::runtime_error(path.string() + ": no planar target (with corners_world)");
  return targets;
}

cv::Mat KnownAlbedoImage(const std::vector<Target>& targets, const GeometryMaps& maps, const CameraRays& rays,
                         const Rigid3d& cam_from_world) {
  const float nan = std::nanf("");
  cv::Mat albedo(maps.depth.size(), CV_32FC3, cv::Scalar::all(nan));
  const Rigid3d world_from_cam = cam_from_world.Inverse();
  for (int row = 0; row < albedo.rows; ++row) {
    for (int col = 0; col < albedo.cols; ++col) {
      const float depth = maps.depth.at<float>(row, col);
      if (std::isnan(depth)) continue;
      const Eigen::Vector3d direction = rays.Direction(col, row).cast<double>();
      const Eigen::Vector3d point_in_world = world_from_cam * ((depth / direction.z()) * direction);
      for (const Target& target : targets) {
        if (target.Contains(point_in_world, 0.005 * depth + 0.002)) {
          albedo.at<cv::Vec3f>(row, col) = cv::Vec3f(static_cast<float>(target.albedo.x()),
                                                     static_cast<float>(target.albedo.y()),
                                                     static_cast<float>(target.albedo.z()));
          break;
        }
      }
    }
  }
  return albedo;
}

}  // namespace lutex
