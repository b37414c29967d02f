#pragma once

// Edge-preserving smoothing of restored albedo, as strong as the noise the image itself shows.
//
// Restoration divides the observed signal by alpha cos_theta. Where alpha is small (far surfaces, the
// edges of the beams, red in turbid water) the sensor's noise is multiplied many times: on the Blender
// turbid seafloor the outer fifth of each image has a red signal of 8 % of the backscatter, and a LUT
// fitted to the test images themselves (an oracle) still leaves a per-pixel error of 11 pp there. Noise
// that strong is removed here, and only where it is that strong:
//
//   1. The noise of each pixel and channel, from the image alone (whatever made it: sensor, compression,
//      path tracing): sigma(x) = 1.383 x the mean of |rho - median3x3(rho)| over the surface pixels of a
//      (2 noise_radius + 1)^2 window, each at most 1 (full scale). For Gaussian noise
//      E|n - median3x3(n)| = 0.723 sigma; texture and edges in the window raise the estimate a little.
//   2. Each surface pixel becomes the weighted mean of the surface pixels of a (2 radius + 1)^2 window,
//      with Tukey's biweight (1 - d^2 / cutoff^2)^2 (0 beyond the cutoff), where
//      d^2 = sum over channels ((rho_c(n) - rho_c(x)) / sigma_c(x))^2: neighbours that differ by more
//      than the noise (another colour, an edge) barely count, so detail above the noise stays and a
//      colour is not smeared over its neighbour (Lee's sigma filter, 1983, with smooth weights). A channel with little noise decides which neighbours are alike for
//      the noisy ones: the green of a turbid image draws the edges the red is averaged within.
//   3. A pixel unlike all its neighbours (their weights sum below 1: an impulse, a hot pixel, a
//      path-tracing firefly) takes the median of its 3 x 3 surface neighbourhood instead.
//   4. Steps 1-3 are repeated `passes` times, each on the last pass's result with its noise measured
//      again: a pass averages what noise the last one left within the same edges, so the window grows
//      pass by pass where noise remains (the outer fifth of a turbid image) and a pass that finds no
//      noise changes next to nothing (README, 'Noise': 1 to 4 passes measured on clear and turbid water).
//
// Pixels without a surface are neither changed nor used; values beyond +-10^6 (an alpha near 0 restores
// to anything) are averaged as +-10^6. Single-threaded per image (images are restored
// in parallel); O(passes x pixels x (2 radius + 1)^2).

#include <opencv2/core.hpp>

namespace lutex {

struct NoiseAdaptiveSmoothingOptions {
  bool enabled = true;
  // Half-size of the averaging window, pixels: at most (2 radius + 1)^2 pixels of one colour averaged,
  // noise divided by up to 2 radius + 1.
  int radius = 2;
  // Half-size of the window the noise is estimated over, pixels.
  int noise_radius = 7;
  // Colour difference, in noise standard deviations (over the three channels), from which a neighbour
  // does not count; its weight is 1/2 at 0.54 x this. 4.685 is the textbook constant of the biweight
  // (95 % efficiency under Gaussian noise); two pixels of one colour differ by a typical 2.45 sigma in
  // three channels, where the weight is 0.53.
  double cutoff = 4.685;
  // Times steps 1-3 run, 1 to 16.
  int passes = 3;
  void Check() const;
};

// `albedo`: CV_32FC3; `surface`: CV_8U, non-zero where the pixel sees a surface. Returns the smoothed
// albedo (a copy of `albedo` when options.enabled is false).
cv::Mat SmoothNoiseAdaptively(const cv::Mat& albedo, const cv::Mat& surface,
                              const NoiseAdaptiveSmoothingOptions& options);

}  // namespace lutex
