#pragma once

// Restoration of one image to albedo with a FrustumLut (paper Eq. 4 with lutex's model, see
// lib/model/image_formation.h): per pixel, the ray-cast depth and normal give the surface point x and
// cos_theta; alpha(x) and beta(x) come from the LUT; rho = (I - beta) / (alpha cos_theta).
//
// Confidence per pixel and channel in [0, 1] (paper, "confidence maps"), the product of
//   signal:     how far the signal (I - beta) stands above the noise: clamp((I - beta) / (k sigma), 0, 1),
//               sigma^2 = shot^2 I + read^2
//   saturation: 0 where the observed value reaches `saturation_level`
//   coverage:   the LUT's data coverage at x (1 where calibration data constrained the nodes; optional)
//   grazing:    GrazingConfidence(cos_theta)
//
// Pixels where the ray meets no surface have no albedo: they are written as 0 with confidence 0 (the
// documented choice; restoring water with the far slab would invent a surface).

#include <opencv2/core.hpp>

#include "lib/lut/frustum_lut.h"
#include "lib/model/image_formation.h"
#include "lib/raycast/camera_rays.h"
#include "lib/raycast/geometry_maps.h"

namespace lutex {

struct RestorationOptions {
  ImageFormationOptions model;
  // Observed linear values at or above this are treated as clipped.
  double saturation_level = 0.98;
  // Noise model of the input images (linear units): sigma^2 = shot_noise^2 * I + read_noise^2.
  double shot_noise = 0.01;
  double read_noise = 0.002;
  // The signal counts as fully trustworthy at `signal_to_noise` sigma.
  double signal_to_noise = 10.0;

  void Check() const;
};

struct RestoredImage {
  cv::Mat albedo;      // CV_32FC3 RGB, linear; 0 where there is no surface
  cv::Mat confidence;  // CV_32FC3 RGB in [0, 1]
};

// `image` is linear RGB CV_32FC3 of the camera of `rays`; `maps` its depth and normals (Render with
// normal = true). `coverage` optional: a LUT whose alpha holds per-node coverage in [0, 1] (calibration
// summary); null means every node is trusted.
RestoredImage RestoreImage(const cv::Mat& image, const GeometryMaps& maps, const CameraRays& rays, const FrustumLut& lut,
                           const RestorationOptions& options, const FrustumLut* coverage = nullptr);
// The same into `restored`, reusing its buffers when they already have the image's size (no fresh memory
// per image of a dive).
void RestoreImage(const cv::Mat& image, const GeometryMaps& maps, const CameraRays& rays, const FrustumLut& lut,
                  const RestorationOptions& options, const FrustumLut* coverage, RestoredImage* restored);

}  // namespace lutex
