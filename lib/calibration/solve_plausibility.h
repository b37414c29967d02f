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
//
// Only observations whose albedo the data can pin are judged. Where the signal of a white surface,
// alpha cos_theta, is below 5 % of what the pixel recorded (far, turbid, outside the beams: the rest is
// backscatter), a 1 % error of beta alone moves the albedo by about 0.2, so a sound LUT restores such an
// observation outside the bounds as readily as a diverged one. alpha there is the water prior's
// (lib/calibration/water_prior.h): four numbers per channel fitted to all the data, which do not run to 0
// node by node where data are thin as the free LUT's nodes can. Where the prior's alpha is 0 (its fit
// explained a channel by backscatter alone) it says nothing, and the observation is judged. Measured: the
// simulated harbour dive of the water and rig sweep (attenuation 1.4-1.6 per m, boards to 3.5 m) had 24 %
// of its red board observations outside the bounds with beta at the truth's level; of those judged, 11 %.

#include <cstddef>

#include <Eigen/Core>

#include "lib/calibration/observations.h"
#include "lib/lut/frustum_lut.h"

namespace lutex {

struct RestoredObservationStats {
  std::size_t count = 0;  // surface observations restored (a correspondence counts twice)
  // Per channel: the fraction of the observations judged (their signal above 5 % of their intensity), the
  // fraction of those restored outside [-0.25, 1.5], and the median restored albedo of all.
  Eigen::Vector3d judged_fraction = Eigen::Vector3d::Ones();
  Eigen::Vector3d implausible_fraction = Eigen::Vector3d::Zero();
  Eigen::Vector3d median_albedo = Eigen::Vector3d::Zero();
};

// Restores every surface observation with `lut`. With `prior` (the water prior's LUT, in the images'
// intensity units) the observations whose signal it puts above 0 but below 5 % of their intensity are
// not judged; without, all are.
RestoredObservationStats RestoreObservations(const FrustumLut& lut, const ObservationSet& observations,
                                             const FrustumLut* prior = nullptr);

// Throws std::runtime_error when, in any channel, more than `max_implausible_fraction` of the judged
// observations restore to implausible albedos, naming the channel, the fraction and the median.
void CheckSolveIsPlausible(const RestoredObservationStats& stats, double max_implausible_fraction = 0.2);

}  // namespace lutex
