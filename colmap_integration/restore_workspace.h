#pragma once

// `lutex restore`: every registered image of a COLMAP workspace restored to albedo with a calibrated LUT,
// plus a per-channel confidence map (lib/restoration/restorer.h). Images are streamed: each is read,
// ray-cast, restored and written by one thread, so memory does not grow with the number of images.
//
// Output:
//   OUTPUT/NAME                the restored image, in `output_encoding` (.png when 16-bit or float
//                              output would not fit the input's extension, e.g. .jpg); OUTPUT defaults
//                              to W/lutex/restored
//   OUTPUT_confidence/NAME.png 8-bit RGB confidence, 255 = 1. A sibling, not a subfolder, so tools that
//                              collect restored images by name under OUTPUT do not pick these up.
// Pixels without a surface are 0 with confidence 0.

#include <cstddef>
#include <filesystem>
#include <string>

#include "lib/image/image_io.h"
#include "lib/restoration/restorer.h"

namespace lutex {

struct RestoreOptions {
  std::filesystem::path workspace;
  std::filesystem::path mesh;
  std::filesystem::path lut;
  // Per-node data coverage of the LUT (lutex calibrate writes it as coverage.lut beside the LUT); it
  // lowers the confidence where no calibration data constrained the LUT. Empty: coverage.lut beside the
  // LUT when it exists, else every node is trusted. `use_coverage` false ignores coverage altogether.
  std::filesystem::path coverage;
  bool use_coverage = true;
  // Empty: W/lutex/restored.
  std::filesystem::path output;
  // How the input images are encoded (the default, 8-bit sRGB, is what cameras' JPEGs are).
  ImageEncoding input_encoding = ImageEncoding::kSrgb8;
  // "same" (as the input), "srgb8", "linear16" or "float" (EXR).
  std::string output_encoding = "same";
  RestorationOptions restoration;
  int num_threads = 0;

  void Check() const;
};

struct RestoreSummary {
  std::filesystem::path output;
  std::filesystem::path coverage;  // the coverage LUT used; empty when none
  std::filesystem::path confidence_output;
  std::size_t num_images = 0;
  double mean_confidence = 0.0;  // over pixels with a surface, all channels
  double seconds = 0.0;
};

// Reads and validates the model, mesh, LUT and the existence of every image before writing anything.
RestoreSummary RestoreWorkspace(const RestoreOptions& options);

}  // namespace lutex
