#pragma once

// How an image was exposed, from its EXIF tags: exposure time (s), ISO speed and f-number. The light a
// pixel records is proportional to t * ISO / N^2 (N the f-number), so images taken at different settings
// are brought to one scale by dividing by that product relative to a reference (calibration records the
// median of its images' products, and restoration divides each image by its own product over it). Read
// through GDAL, which parses the EXIF block of JPEG and TIFF files (tags ExposureTime 0x829A, FNumber
// 0x829D, ISOSpeedRatings 0x8827); other files, and files without the tags, have no settings.
//
// With strobes that fire within the shutter time, the time does not change what the sensor gets; the
// gains fitted per image (lib/calibration/exposure_gains.h), applied on top, take up what EXIF misses.

#include <filesystem>
#include <vector>

namespace lutex {

struct ExposureSettings {
  // 0 where the image does not say.
  double exposure_time_s = 0.0;
  double iso = 0.0;
  double f_number = 0.0;
};

// The settings in `path`'s EXIF tags; all 0 when it has none or is not an image GDAL reads. Throws
// std::runtime_error naming the file when it does not exist.
ExposureSettings ReadExposureSettings(const std::filesystem::path& path);

// Which of the three factors to use: those every image of a set has, so that all are on one scale.
struct ExposureFactors {
  bool exposure_time = false;
  bool iso = false;
  bool f_number = false;

  bool Any() const { return exposure_time || iso || f_number; }
};
ExposureFactors FactorsInEvery(const std::vector<ExposureSettings>& settings);

// t * ISO / N^2 over the factors given: 1 when none is, 0 when the image lacks one of them.
double ExposureProduct(const ExposureSettings& settings, const ExposureFactors& factors);

}  // namespace lutex
