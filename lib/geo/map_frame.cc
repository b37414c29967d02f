#include "lib/geo/map_frame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <proj.h>

namespace lutex {

struct MapFrame::Proj {
  PJ_CONTEXT* context = proj_context_create();
  PJ* enu_to_geodetic = nullptr;  // local ENU (m) -> longitude, latitude (degrees), ellipsoidal height (m)
  PJ* geodetic_to_map = nullptr;  // longitude, latitude (degrees) -> easting, northing

  Proj() { proj_log_level(context, PJ_LOG_NONE); }  // errors are thrown, not printed

  ~Proj() {
    if (geodetic_to_map) proj_destroy(geodetic_to_map);
    if (enu_to_geodetic) proj_destroy(enu_to_geodetic);
    proj_context_destroy(context);
  }

  std::string LastError() const {
    const int code = proj_context_errno(context);
    const char* text = code ? proj_context_errno_string(context, code) : nullptr;
    return text ? text : "unknown PROJ error";
  }
};

namespace {

bool IsProjected(PJ_CONTEXT* context, PJ* crs) {
  const PJ_TYPE type = proj_get_type(crs);
  if (type == PJ_TYPE_PROJECTED_CRS) return true;
  if (type == PJ_TYPE_BOUND_CRS) {  // a CRS with its transformation to WGS 84 (+towgs84, WKT1 TOWGS84)
    PJ* source = proj_get_source_crs(context, crs);
    const bool projected = source && IsProjected(context, source);
    if (source) proj_destroy(source);
    return projected;
  }
  if (type != PJ_TYPE_COMPOUND_CRS) return false;
  PJ* horizontal = proj_crs_get_sub_crs(context, crs, 0);
  const bool projected = horizontal && proj_get_type(horizontal) == PJ_TYPE_PROJECTED_CRS;
  if (horizontal) proj_destroy(horizontal);
  return projected;
}

}  // namespace

std::string UtmCrsOf(double latitude_deg, double longitude_deg) {
  double longitude = std::fmod(longitude_deg + 180.0, 360.0);
  if (longitude < 0.0) longitude += 360.0;
  longitude -= 180.0;
  int zone = static_cast<int>(std::floor((longitude + 180.0) / 6.0)) + 1;
  zone = std::min(zone, 60);
  if (latitude_deg >= 56.0 && latitude_deg < 64.0 && longitude >= 3.0 && longitude < 12.0) zone = 32;
  if (latitude_deg >= 72.0 && latitude_deg < 84.0 && longitude >= 0.0 && longitude < 42.0) {
    zone = longitude < 9.0 ? 31 : longitude < 21.0 ? 33 : longitude < 33.0 ? 35 : 37;
  }
  return "EPSG:" + std::to_string((latitude_deg >= 0.0 ? 32600 : 32700) + zone);
}

MapFrame::MapFrame(const Georeference& georeference) : georeference_(georeference), proj_(std::make_unique<Proj>()) {
  CheckGeoreference(georeference);
  if (!georeference.IsSet()) return;
  crs_ = georeference.crs;
  if (georeference.frame == Georeference::Frame::kEnu && crs_.empty()) {
    crs_ = UtmCrsOf(georeference.origin.x(), georeference.origin.y());
  }
  PJ* crs = proj_create(proj_->context, crs_.c_str());
  if (!crs) throw std::invalid_argument(crs_ + ": the CRS is unknown to PROJ (" + proj_->LastError() + ")");
  const bool projected = IsProjected(proj_->context, crs);
  if (projected) {
    const char* wkt = proj_as_wkt(proj_->context, crs, PJ_WKT2_2019, nullptr);
    const char* name = proj_get_name(crs);
    crs_wkt_ = wkt ? wkt : "";
    crs_name_ = name ? name : crs_;
  }
  proj_destroy(crs);
  if (!projected) {
    throw std::invalid_argument(crs_ + ": not a projected CRS (map products need metres east and north; e.g. a UTM "
                                       "zone, EPSG:326ZZ)");
  }
  PJ* geodetic_to_map = proj_create_crs_to_crs(proj_->context, "EPSG:4326", crs_.c_str(), nullptr);
  if (!geodetic_to_map) throw std::invalid_argument(crs_ + ": no transformation from WGS 84 (" + proj_->LastError() + ")");
  proj_->geodetic_to_map = proj_normalize_for_visualization(proj_->context, geodetic_to_map);  // lon, lat in
  proj_destroy(geodetic_to_map);
  if (!proj_->geodetic_to_map) throw std::invalid_argument(crs_ + ": " + proj_->LastError());
  if (georeference.frame != Georeference::Frame::kEnu) return;
  char pipeline[512];
  std::snprintf(pipeline, sizeof(pipeline),
                "+proj=pipeline +step +inv +proj=topocentric +ellps=WGS84 +lat_0=%.12f +lon_0=%.12f +h_0=%.6f "
                "+step +inv +proj=cart +ellps=WGS84 +step +proj=unitconvert +xy_in=rad +xy_out=deg",
                georeference.origin.x(), georeference.origin.y(), georeference.origin.z());
  proj_->enu_to_geodetic = proj_create(proj_->context, pipeline);
  if (!proj_->enu_to_geodetic) throw std::invalid_argument("the ENU origin: " + proj_->LastError());
}

MapFrame::~MapFrame() = default;

void MapFrame::Convert(std::vector<Eigen::Vector3d>& points, bool to_map) const {
  if (points.empty()) return;
  switch (georeference_.frame) {
    case Georeference::Frame::kNone: return;
    case Georeference::Frame::kProjected:
      for (Eigen::Vector3d& point : points) point += to_map ? georeference_.origin : Eigen::Vector3d(-georeference_.origin);
      return;
    case Georeference::Frame::kEnu: break;
  }
  const std::size_t stride = sizeof(Eigen::Vector3d);
  const std::size_t n = points.size();
  double* x = &points[0].x();
  double* y = &points[0].y();
  double* z = &points[0].z();
  // Heights are the ellipsoidal heights of the ENU step; the CRS step converts only the horizontal.
  if (to_map) {
    proj_trans_generic(proj_->enu_to_geodetic, PJ_FWD, x, stride, n, y, stride, n, z, stride, n, nullptr, 0, 0);
    proj_trans_generic(proj_->geodetic_to_map, PJ_FWD, x, stride, n, y, stride, n, nullptr, 0, 0, nullptr, 0, 0);
  } else {
    proj_trans_generic(proj_->geodetic_to_map, PJ_INV, x, stride, n, y, stride, n, nullptr, 0, 0, nullptr, 0, 0);
    proj_trans_generic(proj_->enu_to_geodetic, PJ_INV, x, stride, n, y, stride, n, z, stride, n, nullptr, 0, 0);
  }
  for (const Eigen::Vector3d& point : points) {
    if (!point.allFinite() || std::abs(point.x()) == HUGE_VAL) {
      throw std::runtime_error("PROJ cannot convert a point between the model and " + crs_ + " (" +
                               proj_->LastError() + ")");
    }
  }
}

Eigen::Vector3d MapFrame::GeodeticFromModel(const Eigen::Vector3d& point_in_model) const {
  if (!georeference_.IsSet()) throw std::invalid_argument("a model that is not georeferenced has no geodetic coordinates");
  Eigen::Vector3d point = point_in_model;
  if (georeference_.frame == Georeference::Frame::kEnu) {
    proj_trans_generic(proj_->enu_to_geodetic, PJ_FWD, &point.x(), 0, 1, &point.y(), 0, 1, &point.z(), 0, 1, nullptr, 0, 0);
  } else {
    point += georeference_.origin;
    proj_trans_generic(proj_->geodetic_to_map, PJ_INV, &point.x(), 0, 1, &point.y(), 0, 1, nullptr, 0, 0, nullptr, 0, 0);
  }
  if (!point.allFinite() || std::abs(point.x()) == HUGE_VAL) {
    throw std::runtime_error("PROJ cannot convert a point of the model to WGS 84 (" + proj_->LastError() + ")");
  }
  return Eigen::Vector3d(point.y(), point.x(), point.z());
}

void MapFrame::MapFromModel(std::vector<Eigen::Vector3d>& points) const { Convert(points, true); }
void MapFrame::ModelFromMap(std::vector<Eigen::Vector3d>& points) const { Convert(points, false); }

Eigen::Vector3d MapFrame::MapFromModel(const Eigen::Vector3d& point_in_model) const {
  std::vector<Eigen::Vector3d> points{point_in_model};
  Convert(points, true);
  return points[0];
}

Eigen::Vector3d MapFrame::ModelFromMap(const Eigen::Vector3d& point_in_map) const {
  std::vector<Eigen::Vector3d> points{point_in_map};
  Convert(points, false);
  return points[0];
}

}  // namespace lutex
