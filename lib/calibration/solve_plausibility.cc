#include "lib/calibration/solve_plausibility.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "lib/model/image_formation.h"

namespace lutex {

namespace {

constexpr double kLowestPlausible = -0.25;
constexpr double kHighestPlausible = 1.5;
// Below this share of its intensity, an observation's signal cannot pin its albedo (header).
constexpr double kJudgedSignalFraction = 0.05;

}  // namespace

RestoredObservationStats RestoreObservations(const FrustumLut& lut, const ObservationSet& observations,
                                             const FrustumLut* prior) {
  std::array<std::vector<double>, 3> albedos, judged;
  // As restoration does it; alpha = 0 gives an infinite or undefined albedo, which counts as implausible.
  const auto restore = [&](const Eigen::Vector2d& pixel, const Eigen::Vector3d& point_in_cam,
                           const Eigen::Vector3d& intensity, double cos_theta) {
    const LutNode node = lut.Lookup(pixel.x(), pixel.y(), point_in_cam.z());
    const Eigen::Vector3d albedo = RestoreAlbedo(node.alpha, node.beta, cos_theta, intensity);
    const Eigen::Vector3d signal =
        prior == nullptr ? Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity())
                         : Eigen::Vector3d(prior->Lookup(pixel.x(), pixel.y(), point_in_cam.z()).alpha * cos_theta);
    for (int c = 0; c < 3; ++c) {
      albedos[c].push_back(albedo[c]);
      const bool starved = signal[c] > 0.0 && signal[c] < kJudgedSignalFraction * intensity[c];
      if (!starved) judged[c].push_back(albedo[c]);
    }
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
    const std::vector<double>& values = judged[c];
    const auto implausible = std::count_if(values.begin(), values.end(), [](double rho) {
      return !(rho >= kLowestPlausible && rho <= kHighestPlausible);
    });
    stats.judged_fraction[c] = static_cast<double>(values.size()) / static_cast<double>(stats.count);
    stats.implausible_fraction[c] =
        values.empty() ? 0.0 : static_cast<double>(implausible) / static_cast<double>(values.size());
    std::vector<double>& all = albedos[c];
    std::nth_element(all.begin(), all.begin() + static_cast<long>(all.size() / 2), all.end());
    stats.median_albedo[c] = all[all.size() / 2];
  }
  return stats;
}

void CheckSolveIsPlausible(const RestoredObservationStats& stats, double max_implausible_fraction) {
  for (int c = 0; c < 3; ++c) {
    if (stats.implausible_fraction[c] <= max_implausible_fraction) continue;
    char text[320];
    std::snprintf(text, sizeof(text),
                  "the calibration diverged: restored with the fitted LUT, %.0f %% of the %zu observations whose "
                  "signal can pin their albedo come out at an albedo outside [%.2f, %.2f] in the %s channel "
                  "(median of all %.3g); no LUT was written",
                  100.0 * stats.implausible_fraction[c],
                  static_cast<std::size_t>(std::lround(stats.judged_fraction[c] * static_cast<double>(stats.count))),
                  kLowestPlausible, kHighestPlausible,
                  c == 0 ? "red" : c == 1 ? "green" : "blue", stats.median_albedo[c]);
    throw std::runtime_error(text);
  }
}

}  // namespace lutex
