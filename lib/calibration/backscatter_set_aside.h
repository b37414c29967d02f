#pragma once

// The backscatter calibration sets aside before it takes forward scattering out of an image
// (lib/raycast/forward_scatter_removal.h: the scattering spreads the light from the surfaces, not the
// backscatter). The backscatter is what the LUT is fitted to find, so calibration with forward scattering
// removed runs twice: the first pass corrects whole images; the second sets aside the first LUT's β at
// each image's exposure (the first pass's EXIF and fitted gains) and samples the images again.

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

#include "lib/calibration/exposure_record.h"
#include "lib/lut/frustum_lut.h"
#include "lib/raycast/geometry_maps.h"

namespace lutex {

struct BackscatterSetAside {
  const FrustumLut* lut = nullptr;           // none: nothing is set aside (the first pass)
  const ExposureRecord* exposure = nullptr;  // none: every image at gain 1

  // β of the LUT at each pixel's surface of image `name` of `images_dir`, times its gain; an empty Mat
  // when there is no LUT.
  cv::Mat For(const GeometryMaps& maps, const std::filesystem::path& images_dir, const std::string& name) const;
};

}  // namespace lutex
