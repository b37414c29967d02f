#include "lib/calibration/exposure_record.h"

#include <nlohmann/json.hpp>

#include "lib/util/file_streams.h"
#include "lib/util/json_fields.h"

namespace lutex {

bool ExposureRecord::HasGainsFor(const std::filesystem::path& images_dir) const {
  if (fitted_gains.empty() || fitted_images.empty()) return false;
  std::error_code error;
  return std::filesystem::equivalent(images_dir, fitted_images, error);
}

double ExposureRecord::GainOf(const std::filesystem::path& images_dir, const std::string& name,
                              bool* missing_exif) const {
  double gain = 1.0;
  if (exif_reference > 0.0) {
    const double product = ExposureProduct(ReadExposureSettings(images_dir / name), exif_factors);
    if (product > 0.0) {
      gain = product / exif_reference;
    } else if (missing_exif != nullptr) {
      *missing_exif = true;
    }
  }
  if (HasGainsFor(images_dir)) {
    const auto fitted = fitted_gains.find(name);
    if (fitted != fitted_gains.end()) gain *= fitted->second;
  }
  return gain;
}

void WriteExposureRecord(const ExposureRecord& record, const std::filesystem::path& path) {
  nlohmann::json json;
  json["comment"] =
      "lutex calibrate: the exposure the LUT is for. Restoration divides each image by (its EXIF t * ISO / N^2 over "
      "the factors marked here, relative to the reference) x (its fitted gain). README, 'Exposure'.";
  json["exif"] = {{"exposure_time", record.exif_factors.exposure_time},
                  {"iso", record.exif_factors.iso},
                  {"f_number", record.exif_factors.f_number},
                  {"reference", record.exif_reference > 0.0 ? nlohmann::json(record.exif_reference) : nlohmann::json()}};
  json["fitted_gains"] = nlohmann::json::object();
  for (const auto& [name, gain] : record.fitted_gains) json["fitted_gains"][name] = gain;
  json["fitted_images"] = record.fitted_images.string();
  WriteFileAtomically(path, std::ios::out, [&json](std::ostream& stream) { stream << json.dump(2) << "\n"; });
}

ExposureRecord ReadExposureRecord(const std::filesystem::path& path) {
  return ReadJsonFile(path, "exposure record", [](const nlohmann::json& root, const std::filesystem::path&) {
    ExpectKeys(root, "", {"comment", "exif", "fitted_gains", "fitted_images"});
    ExposureRecord record;
    record.fitted_images = TextField(root, "fitted_images", "", "");
    if (root.contains("exif")) {
      const nlohmann::json& exif = root["exif"];
      ExpectKeys(exif, "exif", {"exposure_time", "iso", "f_number", "reference"});
      record.exif_factors.exposure_time = exif.value("exposure_time", false);
      record.exif_factors.iso = exif.value("iso", false);
      record.exif_factors.f_number = exif.value("f_number", false);
      if (exif.contains("reference") && !exif["reference"].is_null()) {
        record.exif_reference = NumberField(exif, "reference", "exif", 0.0);
        if (!(record.exif_reference > 0.0)) throw JsonFieldError("exif.reference must be positive");
      }
    }
    if (root.contains("fitted_gains")) {
      if (!root["fitted_gains"].is_object()) throw JsonFieldError("fitted_gains must be an object of image names");
      for (const auto& [name, gain] : root["fitted_gains"].items()) {
        const double value = NumberField(root["fitted_gains"], name, "fitted_gains", 1.0);
        if (!(value > 0.0)) throw JsonFieldError("fitted_gains." + name + " must be positive");
        record.fitted_gains[name] = value;
      }
    }
    return record;
  });
}

}  // namespace lutex
