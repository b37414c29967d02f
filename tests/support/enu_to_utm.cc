#include "tests/support/enu_to_utm.h"

#include <cmath>

#include <proj.h>

namespace lutex::testing {

namespace {

constexpr double kA = 6378137.0;            // WGS 84 semi-major axis
constexpr double kF = 1.0 / 298.257223563;  // and flattening

Eigen::Vector3d EcefOf(double lat, double lon, double h) {
  const double e2 = kF * (2.0 - kF);
  const double n = kA / std::sqrt(1.0 - e2 * std::sin(lat) * std::sin(lat));
  return {(n + h) * std::cos(lat) * std::cos(lon), (n + h) * std::cos(lat) * std::sin(lon),
          (n * (1.0 - e2) + h) * std::sin(lat)};
}

}  // namespace

Eigen::Vector3d ProjectedOfEnu(const Eigen::Vector3d& point_in_enu, double lat_deg, double lon_deg, double h,
                               const char* crs) {
  const double lat = lat_deg * M_PI / 180.0, lon = lon_deg * M_PI / 180.0;
  const Eigen::Vector3d east(-std::sin(lon), std::cos(lon), 0.0);
  const Eigen::Vector3d north(-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat));
  const Eigen::Vector3d up(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
  const Eigen::Vector3d ecef =
      EcefOf(lat, lon, h) + point_in_enu.x() * east + point_in_enu.y() * north + point_in_enu.z() * up;
  PJ_CONTEXT* context = proj_context_create();
  PJ* raw = proj_create_crs_to_crs(context, "EPSG:4978", crs, nullptr);
  PJ* transform = proj_normalize_for_visualization(context, raw);
  const PJ_COORD out = proj_trans(transform, PJ_FWD, proj_coord(ecef.x(), ecef.y(), ecef.z(), 0.0));
  proj_destroy(transform);
  proj_destroy(raw);
  proj_context_destroy(context);
  return {out.xyz.x, out.xyz.y, out.xyz.z};
}

}  // namespace lutex::testing
