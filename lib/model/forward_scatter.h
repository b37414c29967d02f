#pragma once

// Forward scattering on the way from a surface to the camera: the veiling light of turbid water.
//
// Light leaving a surface point is scattered a little off its path by particles in the water and reaches
// the camera in other pixels, so each pixel also shows its surroundings, the lit centre of the image most
// of all. On a uniform board this light is proportional to the board's albedo and the LUT's alpha absorbs
// it; on a textured surface it is proportional to the albedo of the neighbours, not of the pixel, and no
// per-pixel LUT can undo it: the restored surface loses contrast (Blender turbid seafloor: restored red
// regressed on the true albedo with slope 0.73 in the image's centre, white and black ColorChecker patches
// pulled towards the grey surround). lutex removes it from every image before the LUT is fitted or
// applied, with the same model in calibration and restoration.
//
// The model, per channel c, for a pixel whose surface lies at range d along its ray:
//   S = t R + (1 - t) (k * R),   t = exp(-b_c d)
// S is the signal the camera records (backscatter is treated by the LUT: it varies smoothly and the
// correction leaves it as it is), R the signal that left the pixel's own surface point, t the part of it
// that reaches the camera unscattered, and (1 - t) the part scattered once on the way, which arrives from
// the directions around the pixel with the angular kernel k. The model conserves energy: a uniform surface
// under uniform light is unchanged.
//
// The kernel follows from the water's Henyey-Greenstein phase function p (anisotropy g). A ray scattered
// at distance s of the d along its path, by the angle theta, meets a surface at distance d seen from the
// camera at phi = theta (1 - s / d) (small angles). Integrating over s uniformly along the path,
//   k(phi) = (1 / phi) * integral from phi to pi of p(theta) dtheta
// per steradian, normalised to 1 over the hemisphere. It does not depend on d: near pixels and far ones
// are blurred by the same angles, and only the amount (1 - t) grows with range. It is sharply peaked
// (the 1 / phi core) with a long tail (for g = 0.9 a quarter of the scattered light arrives from more than
// 10 degrees away), which is what brightens the dark edges of an image with the lit centre.
//
// Images are convolved with k as a sum of Gaussians, one per octave of angle: the kernel's energy
// between the octave's bounds (its radial distribution) goes to a Gaussian of that width, wide ones
// applied on a downsampled image, so the cost per pixel does not grow with the image's size. The part of
// the kernel within 3.3 pixels (the finest Gaussian has sigma 4 px) stays on the pixel: undoing finer blur
// would mostly amplify the pixels' noise (forward_scatter.cc says what that choice was measured on). Pixel
// distances are converted to angles with the camera's focal length (phi = atan(r / f)), so a sharper
// camera sees more of the blur as blur.
//
// Inverting: t R + (1 - t) (k * R) = S is solved by Chebyshev iteration (forward_scatter.cc says why it
// converges and how fast: where 70 % of the light is scattered, its bound leaves under 1 % of the
// correction undone after 4 steps, one convolution each; the plain series R = S - (1 - t) (k * R - R)
// leaves 2.5 % after 8). Radiance is not negative: where the scattering given exceeds the water's, dark pixels beside
// bright ones would come out below 0, and are set to 0.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "lib/model/water.h"

namespace lutex {

struct ForwardScatter {
  // b per channel [1/m]; zero: no forward scattering (clear water at short range, air).
  Eigen::Vector3d scattering = Eigen::Vector3d::Zero();
  // Henyey-Greenstein anisotropy of the water's particles.
  double anisotropy_g = 0.9;

  // The scattering and phase function of `water`.
  static ForwardScatter Of(const Water& water);
  bool IsNone() const { return scattering.isZero(); }
  // Throws std::invalid_argument naming the problem (negative or non-finite b, g outside [0, 1)).
  void Check() const;
  bool operator==(const ForwardScatter& other) const {
    return scattering == other.scattering && anisotropy_g == other.anisotropy_g;
  }
};

// "b 0.402 0.402 0.402 per m (r g b), g 0.90", for messages.
std::string DescribeForwardScatter(const ForwardScatter& scatter);

// The fraction of the kernel k's energy within angle `phi_rad` of its centre (0 at 0, 1 at pi / 2).
double ForwardScatterEnergyWithin(double phi_rad, double anisotropy_g);

// k in an image of focal length `focal_px` as a sum of Gaussians: `identity_weight` stays on the pixel,
// and weight[i] is spread by a Gaussian of sigma_px[i] pixels. The weights sum to 1.
struct ForwardScatterKernel {
  double identity_weight = 1.0;
  std::vector<double> sigma_px;
  std::vector<double> weight;
};
ForwardScatterKernel MakeForwardScatterKernel(double anisotropy_g, double focal_px);

// k * image for a CV_32FC3 image (edges mirrored).
cv::Mat ConvolveForwardScatterKernel(const cv::Mat& image, const ForwardScatterKernel& kernel);

// The signal after forward scattering, t R + (1 - t) (k * R), of a CV_32FC3 radiance image; `range` is
// CV_32F, the distance [m] from the camera to each pixel's surface along its ray, NaN where there is none
// (there t = 1). What lutex's simulator renders with (lib/model/simulator.h, off unless a scene asks).
cv::Mat AddForwardScatter(const cv::Mat& radiance, const cv::Mat& range, const ForwardScatterKernel& kernel,
                          const Eigen::Vector3d& scattering_per_m);

// R from S by the iteration above (`iterations` convolutions), for a CV_32FC3 image and its range map.
cv::Mat RemoveForwardScatter(const cv::Mat& image, const cv::Mat& range, const ForwardScatterKernel& kernel,
                             const Eigen::Vector3d& scattering_per_m, int iterations = 4);

}  // namespace lutex
