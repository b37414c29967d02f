#pragma once

// Pure-water observations (paper Eq. "beta_N <= I_pw"): images of open water, no surface in view, whose
// every pixel bounds the backscatter along its ray. An image that does show a surface (the seafloor at the
// edge of the light, a fish, the frame of the vehicle) still gives valid but loose bounds, so it is not
// wrong to use; it is screened out anyway because it says the user's "pure water" folder is not what it
// claims, and one bright frame would otherwise carry no information at all.
//
// Screening, per image and against the set:
//   structure: backscatter is smooth across the image; the fraction of pixels (on a 160-pixel-wide
//              thumbnail, 3 x 3 median-filtered so isolated outliers do not count) that depart from its
//              smooth fit (a local quadratic over 39 pixels, the image continued past its edges by point
//              reflection, so curved gradients and gradients into the border are fitted) by more than
//              0.003 + 5 % and by more than 5 times the image's own noise (from second differences, which
//              a surface filling the frame does not inflate) is the image's structure. Above
//              `max_structure` (1 %) a surface edge is in view.
//   brightness: a surface lit by the rig is far brighter than backscatter; an image whose mean in any
//              channel exceeds `max_brightness_ratio` (4) times the set's lower quartile plus 0.002
//              shows one (the quartile stays open water while up to three images in four do not).
// Measured: Blender pure water 0 % structure in clear and turbid water (before the median: 0.07-0.09 %
// clear, 1.1-1.5 % turbid, all of it Monte Carlo fireflies, which rejected every turbid frame), so is the
// simulator's in clear, coastal and harbour water, in harbour water also exposed for it (brightest channel
// at 0.35 of full scale; a Gaussian-smoothed copy left 5-6 % there and rejected it); the turbid Blender
// seafloor 2.1-2.9 %, the clear one 43-50 %, a harbour seafloor seen at 1.8 m 1.5-4.8 %, a seafloor of two
// colours filling the frame 94 % (0 % before the noise came from second differences); frames filled by a
// colour board have none but are 11 to 1000 times brighter than open water, as a uniform seafloor filling
// a simulated frame is 13 times.

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "lib/calibration/observations.h"

namespace lutex {

struct PureWaterScreeningOptions {
  double max_structure = 0.01;
  double max_brightness_ratio = 4.0;

  void Check() const;
};

struct PureWaterImageStats {
  double structure = 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();  // linear RGB
};

// `linear`: RGB CV_32FC3.
PureWaterImageStats MeasurePureWaterImage(const cv::Mat& linear);

// Per image of the set, the reason it seems to show a surface, or empty when it looks like pure water.
std::vector<std::string> ScreenPureWaterImages(const std::vector<PureWaterImageStats>& images,
                                               const PureWaterScreeningOptions& options);

// Every `stride`-th pixel of the image (both directions), as an upper bound on beta along its ray.
std::vector<PureWaterObservation> SamplePureWater(const cv::Mat& linear, int stride);

}  // namespace lutex
