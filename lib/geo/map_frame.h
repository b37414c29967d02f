#pragma once

// The map frame of a georeferenced model: converts between the model's frame and the coordinates of the
// map products (easting, northing, height in a projected CRS), with PROJ.
//
//   projected   map = model + origin, in the model's CRS (no PROJ transform; the CRS is checked).
//   enu         model (east, north, up of the local tangent frame, WGS 84) -> geodetic -> the map CRS:
//               `Georeference::crs`, or the UTM zone of the origin (EPSG:326ZZ north, 327ZZ south).
//               Heights are ellipsoidal.
//   none        map = model, with no CRS: map products in the model's own frame (x east, y north is then
//               only a convention: a warning says the products will not sit on a map).
//
// Not thread-safe (PROJ objects belong to one context): convert in batches from one thread.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lib/geo/georeference.h"

namespace lutex {

class MapFrame {
 public:
  // Throws std::invalid_argument with PROJ's own words when the CRS is unknown or not a projected CRS
  // ("EPSG:999999: the CRS is unknown to PROJ (crs not found)").
  explicit MapFrame(const Georeference& georeference);
  ~MapFrame();
  MapFrame(const MapFrame&) = delete;
  MapFrame& operator=(const MapFrame&) = delete;

  const Georeference& georeference() const { return georeference_; }
  bool HasCrs() const { return !crs_.empty(); }
  // The map CRS as given ("EPSG:32632"), empty without one.
  const std::string& crs() const { return crs_; }
  // Its WKT (for GeoTIFF), empty without one.
  const std::string& crs_wkt() const { return crs_wkt_; }
  // Its name as PROJ gives it ("WGS 84 / UTM zone 32N").
  const std::string& crs_name() const { return crs_name_; }

  // In place, for many points at once; throws std::runtime_error when PROJ cannot convert a point.
  void MapFromModel(std::vector<Eigen::Vector3d>& points) const;
  void ModelFromMap(std::vector<Eigen::Vector3d>& points) const;

  Eigen::Vector3d MapFromModel(const Eigen::Vector3d& point_in_model) const;

  // Latitude, longitude (degrees, WGS 84) and height (metres) of a point of the model; a projected
  // frame's heights are taken as ellipsoidal, as an ENU frame's are. Throws std::invalid_argument for a
  // model that is not georeferenced.
  Eigen::Vector3d GeodeticFromModel(const Eigen::Vector3d& point_in_model) const;
  Eigen::Vector3d ModelFromMap(const Eigen::Vector3d& point_in_map) const;

 private:
  void Convert(std::vector<Eigen::Vector3d>& points, bool to_map) const;

  Georeference georeference_;
  std::string crs_;
  std::string crs_wkt_;
  std::string crs_name_;
  struct Proj;
  std::unique_ptr<Proj> proj_;
};

// The UTM zone's CRS ("EPSG:32632") of a geodetic point (degrees), with Norway's and Svalbard's exceptions.
std::string UtmCrsOf(double latitude_deg, double longitude_deg);

}  // namespace lutex
