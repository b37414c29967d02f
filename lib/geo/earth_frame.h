#pragma once

// Earth-centred, Earth-fixed coordinates (ECEF, EPSG:4978: metres, WGS 84; x through the equator at
// Greenwich, z through the north pole): where 3D Tiles place a tileset on the globe.

#include <Eigen/Core>

#include "lib/geo/map_frame.h"

namespace lutex {

// Latitude, longitude (degrees) and ellipsoidal height (metres) on WGS 84 to ECEF.
Eigen::Vector3d EcefFromGeodetic(const Eigen::Vector3d& latitude_longitude_height);

// The affine map from a georeferenced model's frame to ECEF, exact at `point_in_model` and to first order
// around it: its columns are the model's axes in ECEF, from central differences of 1 m. For an ENU frame
// the map is a rotation; a projected CRS's grid also carries its scale factor and meridian convergence
// (a 500 m survey in UTM is off by millimetres at its edges). Throws std::invalid_argument for a model
// that is not georeferenced.
Eigen::Matrix4d EcefFromModelNear(const MapFrame& frame, const Eigen::Vector3d& point_in_model);

}  // namespace lutex
