#pragma once

// Where a model sits on the Earth. A COLMAP model aligned to navigation data (`colmap model_aligner`) is
// in one of two frames, and only the user knows which:
//
//   projected   a projected CRS shifted to a local origin: model (x, y, z) + origin = (easting, northing,
//               height) in `crs` (e.g. EPSG:32632, UTM 32N). x is east, y north, z up.
//   enu         a local east-north-up frame, tangent to the WGS 84 ellipsoid at the geodetic point
//               `origin` = (latitude, longitude in degrees, ellipsoidal height in metres), as
//               `model_aligner --ref_is_gps 1 --alignment_type enu` leaves it. Map products of an ENU
//               model are in `crs` when one is given, else in the UTM zone of the origin.
//   none        not georeferenced: map products are in the model's own frame, with no CRS.
//
// The georeference file (W/georef.json, which every command and `lutex run` find in the workspace):
//
//   {"frame": "projected", "crs": "EPSG:32632", "origin": [500123.0, 6001234.0, -812.5]}
//   {"frame": "enu", "origin": [54.3201, 10.1402, 0.0]}             (optional "crs" for the map products)
//
// Coordinates are doubles end to end.

#include <filesystem>
#include <string>

#include <Eigen/Core>

namespace lutex {

struct Georeference {
  enum class Frame { kNone, kProjected, kEnu };
  Frame frame = Frame::kNone;
  std::string crs;  // projected: the model's CRS; enu: the map products' CRS, empty for the origin's UTM zone
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // see above

  bool IsSet() const { return frame != Frame::kNone; }
  // "EPSG:32632 + (500123.000, 6001234.000, -812.500)" or "ENU at 54.3201000 N, 10.1402000 E, 0.000 m".
  std::string Describe() const;
};

// "none", "projected", "enu".
std::string FrameName(Georeference::Frame frame);

// "X,Y,Z" (three finite numbers, commas, optional spaces) as a vector; throws std::invalid_argument
// naming `what` otherwise.
Eigen::Vector3d ParseTriple(const std::string& text, const std::string& what);

// Throws std::invalid_argument when the origin is not finite, an ENU origin's latitude is outside
// [-90, 90] or its longitude outside [-180, 360], or a projected frame has no CRS. CRS codes are checked
// by MapFrame, which knows PROJ.
void CheckGeoreference(const Georeference& georeference);

// The georeference file; throws std::runtime_error starting with the path when it cannot be read or
// holds anything else.
Georeference ReadGeoreference(const std::filesystem::path& path);
// Writes it (atomically).
void WriteGeoreference(const Georeference& georeference, const std::filesystem::path& path);

}  // namespace lutex
