#pragma once

// What a LUT assumes about exposure, written by calibration beside the LUT (`exposure.json`) and read by
// restoration: the EXIF factors calibration used and their reference product (the median of its images':
// the LUT is for an image exposed at that product), and the gain fitted per survey image
// (lib/calibration/exposure_gains.h) with the folder their names are in. An image is restored as
// I / gain, with
//   gain = (its EXIF product / reference, when the record has a reference and the image the factors; else 1)
//          x (its fitted gain, when it is in that folder and the record lists its name; else 1).
// Camera file names repeat from dive to dive, so another dive restored with this LUT gets EXIF only.
//
// File (JSON):
//   {"exif": {"exposure_time": true, "iso": true, "f_number": false, "reference": 0.004},  ("reference": null
//                                                                                    when no factor is used)
//    "fitted_gains": {"NAME": 0.97, ...},        (the workspace's images, by their name in the model)
//    "fitted_images": "/abs/W/images",           (the folder those names are in)
//    "comment": "..."}

#include <filesystem>
#include <map>
#include <string>

#include "lib/image/exposure_settings.h"

namespace lutex {

struct ExposureRecord {
  ExposureFactors exif_factors;
  double exif_reference = 0.0;  // 0: EXIF not used
  std::map<std::string, double> fitted_gains;
  std::filesystem::path fitted_images;  // absolute

  // Whether `images_dir` is the folder of the fitted gains' images.
  bool HasGainsFor(const std::filesystem::path& images_dir) const;
  // The gain of image `name` (its name in its model) of `images_dir`: see above. An image without the
  // EXIF factors the record uses gets EXIF gain 1 (`missing_exif` set, when given).
  double GainOf(const std::filesystem::path& images_dir, const std::string& name, bool* missing_exif = nullptr) const;
};

void WriteExposureRecord(const ExposureRecord& record, const std::filesystem::path& path);
// Throws std::runtime_error naming the file when it cannot be read or is not such a record.
ExposureRecord ReadExposureRecord(const std::filesystem::path& path);

}  // namespace lutex
