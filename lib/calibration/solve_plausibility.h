#pragma once

// Whether a fitted LUT is physically plausible on the very observations it was fitted to. Every surface
// observation (known colour, or either view of a correspondence) is restored with the LUT as restoration
// does it (RestoreAlbedo, lib/model/image_formation.h), rho = (I - beta) / (alpha cos_theta), per channel. A sane solve gives albedos in [0, 1] up to noise. A
// solve that diverged (alpha driven towards 0, beta above the signal: seen with a light rig, whose
// correspondences alone leave a factor per channel free) gives albedos in the thousands or below zero.
// Such a LUT must never be written: it would restore a whole dive to nonsense.
//
// "Implausible" is an albedo outside [-0.25, 1.5]. The bounds are physical: albedo lies in [0, 1], and
// the margins absorb noise, dark pixels and slight over-exposure. They are not tuned to any data set.

#include <cstddef>

#include <Eigen/Core>

#include "lib/calibration/observations.h"
#include "lib/lut/frustum_lut.h"

namespace lutex {

struct RestoredObservationStats {
  std::size_t count = 0;  // surface observations restored (a correspondence counts twice)
  // Per channel: the fraction restored outside [-0.25, 1.5], and the median restored albedo.
  Eigen::Vector3d implausible_fraction = Eigen::Vector3d::Zero();
  Eigen::Vector3d median_albedo = Eigen::Vector3d::Zero();
};

RestoredObservationStats RestoreObservations(const FrustumLut& lut, const ObservationSet& observations);

// Throws std::runtime_error when, in any channel, more than `max_implausible_fraction` of the observations
// restore to implausible albedos, naming the channel, the fraction and the median.
void CheckSolveIsPlausible(const RestoredObservationStats& stats, double max_implausible_fraction = 0.2);

}  // namespace lutex
