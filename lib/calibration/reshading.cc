#include "lib/calibration/reshading.h"

#include <algorithm>

namespace lutex {

void Reshade(const Shading& shading, double min_cos_theta, ObservationSet* observations) {
  const auto reshade = [&](const Eigen::Vector3d& point_in_cam, const Eigen::Vector3d& normal_in_cam, double* cos_theta) {
    *cos_theta = shading.Cosine(point_in_cam, normal_in_cam);
    return *cos_theta >= min_cos_theta;
  };
  auto& known = observations->known_colors;
  known.erase(std::remove_if(known.begin(), known.end(),
                             [&](KnownColorObservation& o) { return !reshade(o.point_in_cam, o.normal_in_cam, &o.cos_theta); }),
              known.end());
  auto& pairs = observations->correspondences;
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                             [&](CorrespondenceObservation& o) {
                               const bool first = reshade(o.first.point_in_cam, o.first.normal_in_cam, &o.first.cos_theta);
                               const bool second = reshade(o.second.point_in_cam, o.second.normal_in_cam, &o.second.cos_theta);
                               return !first || !second;
                             }),
              pairs.end());
}

}  // namespace lutex
