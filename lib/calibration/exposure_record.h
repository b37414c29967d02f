#pragma once

// What a LUT assumes about exposure, written by calibration beside the LUT (`exposure.json`) and read by
// restoration: the EXIF factors calibration used and their reference product (the median of its images':
// the LUT is for an image exposed at that product), and the gain fitted per survey image
// (lib/calibration/exposure_gains.h). An image is restored as I / gain, with
//   gain = (its EXIF product / reference, when the record has a reference and the image the factors; else 1)
//          x (its fitted gain, when the record lists its name; else 1).
//
// File (JSON):
//   {"exif": {"exposure_time": true, "iso": true, "f_number": false, "reference": 0.004},  ("reference": null
//                                                                                    when no factor is used)
//    "fitted_gains": {"NAME": 0.97, ...},        (the workspace's images, by their name in the model)
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

  // The gain of the image at `path` (named `name` in its model): see above. An image without the EXIF
  // factors the record uses gets EXIF gain 1 (`missing_exif` set, when given).
  double GainOf(const std::filesystem::path& path, const std::string& name, bool* missing_exif = nullptr) const;
};

void WriteExposureRecord(const ExposureRecord& record, const std::filesystem::path& path);
// Throws std::runtime_error naming the file when it cannot be read or is not such a record.
ExposureRecord ReadExposureRecord(const std::filesystem::path& path);

}  // namespace lutex
