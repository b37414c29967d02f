#pragma once

// Filling one lane of an Embree 16-ray packet with a primary ray (internal to ray casting and its
// benchmark; includes Embree, so public headers must not include it).

#include <embree3/rtcore.h>

#include <limits>

#include <Eigen/Core>

namespace lutex {

inline void SetPacketRay(int lane, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                         RTCRayHit16* packet) {
  packet->ray.org_x[lane] = origin.x();
  packet->ray.org_y[lane] = origin.y();
  packet->ray.org_z[lane] = origin.z();
  packet->ray.dir_x[lane] = direction.x();
  packet->ray.dir_y[lane] = direction.y();
  packet->ray.dir_z[lane] = direction.z();
  packet->ray.tnear[lane] = 0.0f;
  packet->ray.tfar[lane] = std::numeric_limits<float>::infinity();
  packet->ray.mask[lane] = 0xFFFFFFFFu;
  packet->ray.time[lane] = 0.0f;
  packet->ray.flags[lane] = 0;
  packet->hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
}

}  // namespace lutex
