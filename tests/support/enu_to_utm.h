#pragma once

// An oracle for the ENU georeference, independent of the PROJ pipeline lib/geo/map_frame.cc builds: a
// point of the local east-north-up frame tangent to WGS 84 at (lat, lon, h) converted to ECEF by the closed
// form, then to a projected CRS by PROJ's own EPSG:4978 -> CRS transformation. Returns easting, northing,
// ellipsoidal height.

#include <Eigen/Core>

namespace lutex::testing {

Eigen::Vector3d ProjectedOfEnu(const Eigen::Vector3d& point_in_enu, double lat_deg, double lon_deg, double h,
                               const char* crs);

}  // namespace lutex::testing
