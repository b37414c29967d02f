#pragma once

// One exposure gain per image, fitted under a LUT. Strobes fire with a few percent of power variation and
// many cameras run auto exposure, so image i records I = g_i (alpha cos_theta rho + beta): the gain
// scales the whole image, backscatter included. With the LUT held fixed, the gains are what makes the
// observations agree:
//   - a known colour seen in image i:        log I = log g_i + log(alpha cos_theta rho_known + beta)
//   - a surface point seen in images a and b: log I_a = log g_a + log(alpha_a cos_a rho_b + beta_a), where
//     rho_b = (I_b / g_b - beta_b) / (alpha_b cos_b) is what image b restores it to (and the same from b's side).
// Residuals are these log ratios (so a gain is fitted relative to the image's own brightness, whatever
// the channel), per channel, under a Cauchy loss that lets a mismatched correspondence (a moving fish, a
// specular glint) count less; its scale follows the residuals' own spread after a least-squares first
// pass (on the Blender seafloor a fixed 5 % scale took the LUT's own errors for mismatches and let the
// gains drift to 0.70 - 1.93 where the truth is 1). Solved for log g by iteratively reweighted Gauss-Newton on normal
// equations of one unknown per image (Eigen's sparse LDLT; a pair of images that share correspondences is
// one off-diagonal entry), streaming over the observations at every iteration: memory grows with the
// images and their overlaps, not with the observations, and one thread gives the same result anywhere.
// Only channels whose signal stands clear of
// noise and backscatter count (`min_intensity`, `min_signal_fraction`).
//
// Only images in a group with correspondences get a gain (see below); the rest keep 1: an image that
// shows only known colours (a board, at one distance) would have its gain trade with the LUT's fall-off
// at that distance. Known colours in a group with correspondences anchor its gains absolutely.
//
// Gauge: correspondences fix gains mostly relative to each other (only backscatter, which a gain scales
// too but the LUT fixes, ties them to an absolute level, weakly; in air nothing does). Images linked by
// correspondences form groups; a group with a known colour in it is fixed by the known colours, any other
// group's gains are scaled to a geometric mean of 1 (the LUT, fitted again, is then for the group's mean
// exposure). An image with no usable observation keeps gain 1.
//
// Calibration alternates: fit the LUT, fit the gains under it, divide them out of the observations
// (DivideOutExposureGains), fit the LUT again (colmap_integration/stages/calibrate_workspace.cc).

#include <cstddef>
#include <vector>

#include "lib/calibration/observations.h"
#include "lib/lut/frustum_lut.h"

namespace lutex {

struct ExposureGainOptions {
  // A channel of an observation counts when its observed value is at least this (linear) ...
  double min_intensity = 0.01;
  // ... and at least this fraction of it is signal rather than backscatter (I - beta >= f I).
  double min_signal_fraction = 0.2;
  // Known-colour channel observations per image, and correspondences per pair of images, used at most;
  // those beyond (in the set's order) are left out, so the time per iteration grows with the number of
  // images and their overlaps, not with the observations.
  int max_known_colors_per_image = 1000;
  int max_correspondences_per_pair = 200;
  int max_iterations = 50;  // per phase (least squares, then the Cauchy loss)

  void Check() const;
};

struct ExposureGains {
  std::vector<double> gains;                    // per ObservationSet::images; 1 where not fitted
  std::vector<std::size_t> num_residuals;       // per image: the channel observations that fitted it (0: no gain)
  std::vector<bool> fixed_by_known_colors;      // per image: its group has known colours (else: mean 1)
};

ExposureGains FitExposureGains(const ObservationSet& observations, const FrustumLut& lut,
                               const ExposureGainOptions& options = {});

// Divides every observation's intensity by its image's gain (observations with image -1 are left alone).
// `gains` has one entry per observations->images.
void DivideOutExposureGains(const std::vector<double>& gains, ObservationSet* observations);

}  // namespace lutex
