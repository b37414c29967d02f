#include "lib/calibration/solve_plausibility.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "lib/model/image_formation.h"

namespace lutex {

namespace {

constexpr double kLowestPlausible = -0.25;
constexpr double kHighestPlausible = 1.5;

}  // namespace

RestoredObservationStats RestoreObservations(const FrustumLut& lut, const ObservationSet& observations) {
  std::array<std::vector<double>, 3> albedos;
  // As restoration does it; alpha = 0 gives an infinite or undefined albedo, which counts as implausible.
  const auto restore = [&](const Eigen::Vector2d& pixel, const Eigen::Vector3d& point_in_cam,
                           const Eigen::Vector3d& intensity, double cos_theta) {
    const LutNode node = lut.Lookup(pixel.x(), pixel.y(), point_in_cam.z());
    const Eigen::Vector3d albedo = RestoreAlbedo(node.alpha, node.beta, cos_theta, intensity);
    for (int c = 0; c < 3; ++c) albedos[c].push_back(albedo[c]);
  };
  for (const KnownColorObservation& o : observations.known_colors) restore(o.pixel, o.point_in_cam, o.intensity, o.cos_theta);
  for (const CorrespondenceObservation& o : observations.correspondences) {
    for (const SurfaceView* view : {&o.first, &o.second}) {
      restore(view->pixel, view->point_in_cam, view->intensity, view->cos_theta);
    }
  }
  RestoredObservationStats stats;
  stats.count = albedos[0].size();
  if (stats.count == 0) return stats;
  for (int c = 0; c < 3; ++c) {
    std::vector<double>& values = albedos[c];
    const auto implausible = std::count_if(values.begin(), values.end(), [](double rho) {
      return !(rho >= kLowestPlausible && rho <= kHighestPlausible);
    });
    stats.implausible_fraction[c] = static_cast<double>(implausible) / static_cast<double>(values.size());
    std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2), values.end());
    stats.median_albedo[c] = values[values.size() / 2];
  }
  return stats;
}

void CheckSolveIsPlausible(const RestoredObservationStats& stats, double max_implausible_fraction) {
  for (int c = 0; c < 3; ++c) {
    if (stats.implausible_fraction[c] <= max_implausible_fraction) continue;
    char text[320];
    std::snprintf(text, sizeof(text),
                  "the calibration diverged: restored with the fitted LUT, %.0f %% of the %zu observations come out "
                  "at an albedo outside [%.2f, %.2f] in the %s channel (median %.3g); no LUT was written",
                  100.0 * stats.implausible_fraction[c], stats.count, kLowestPlausible, kHighestPlausible,
                  c == 0 ? "red" : c == 1 ? "green" : "blue", stats.median_albedo[c]);
    throw std::runtime_error(text);
  }
}

}  // namespace lutex
