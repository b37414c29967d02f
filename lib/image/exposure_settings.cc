#include "lib/image/exposure_settings.h"

#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <string>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>

namespace lutex {

namespace {

// GDAL writes EXIF rationals as "(0.008)" and counts as "400" (or "100 100" for several values): the
// first number in the text, 0 when there is none or it is not positive.
double FirstNumber(const char* text) {
  if (text == nullptr) return 0.0;
  const std::string value(text);
  const std::size_t start = value.find_first_of("0123456789.");
  if (start == std::string::npos) return 0.0;
  const double number = std::strtod(value.c_str() + start, nullptr);
  return number > 0.0 ? number : 0.0;
}

// The tag in the default metadata domain (the JPEG driver's) or in "EXIF" (where other drivers put it).
double ExifNumber(GDALDatasetH dataset, const char* key) {
  const double value = FirstNumber(GDALGetMetadataItem(dataset, key, nullptr));
  return value > 0.0 ? value : FirstNumber(GDALGetMetadataItem(dataset, key, "EXIF"));
}

}  // namespace

ExposureSettings ReadExposureSettings(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw std::runtime_error(path.string() + ": no such image");
  static std::once_flag registered;
  std::call_once(registered, [] { GDALAllRegister(); });
  // Quiet, and only the file itself (no .aux.xml beside it is read or written), from opening to closing;
  // both settings are per thread.
  CPLPushErrorHandler(CPLQuietErrorHandler);
  CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", "NO");
  const char* const drivers[] = {"JPEG", "GTiff", nullptr};
  ExposureSettings settings;
  if (GDALDatasetH dataset = GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, drivers, nullptr, nullptr)) {
    settings.exposure_time_s = ExifNumber(dataset, "EXIF_ExposureTime");
    settings.iso = ExifNumber(dataset, "EXIF_ISOSpeedRatings");
    settings.f_number = ExifNumber(dataset, "EXIF_FNumber");
    GDALClose(dataset);
  }
  CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", nullptr);
  CPLPopErrorHandler();
  return settings;
}

ExposureFactors FactorsInEvery(const std::vector<ExposureSettings>& settings) {
  ExposureFactors factors;
  if (settings.empty()) return factors;
  factors.exposure_time = factors.iso = factors.f_number = true;
  for (const ExposureSettings& s : settings) {
    factors.exposure_time = factors.exposure_time && s.exposure_time_s > 0.0;
    factors.iso = factors.iso && s.iso > 0.0;
    factors.f_number = factors.f_number && s.f_number > 0.0;
  }
  return factors;
}

double ExposureProduct(const ExposureSettings& settings, const ExposureFactors& factors) {
  double product = 1.0;
  if (factors.exposure_time) product *= settings.exposure_time_s;
  if (factors.iso) product *= settings.iso;
  if (factors.f_number) {
    if (!(settings.f_number > 0.0)) return 0.0;
    product /= settings.f_number * settings.f_number;
  }
  return product;
}

}  // namespace lutex
