#pragma once

// `lutex restore`: every registered image of a COLMAP workspace restored to albedo with a calibrated LUT,
// plus a per-channel confidence map (lib/restoration/restorer.h). Images are streamed: each is read,
// ray-cast, restored and written by one thread, so memory does not grow with the number of images.
//
// Each image is first divided by its exposure gain: its EXIF exposure relative to the LUT's and its gain
// fitted in calibration, from `exposure.json` beside the LUT (lib/calibration/exposure_record.h) when there
// is one.
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
#include <ostream>
#include <string>
#include <vector>

#include "colmap_integration/stages/loaded_dive.h"
#include "lib/image/image_io.h"
#include "lib/restoration/noise_adaptive_smoothing.h"
#include "lib/restoration/restorer.h"

namespace lutex {

struct RestoreOptions {
  std::filesystem::path workspace;
  std::filesystem::path mesh;
  std::filesystem::path lut;
  // Per-node data coverage of the LUT (lutex calibrate writes it as coverage.lut beside the LUT); it
  // lowers the confidence where no calibration data constrained the LUT. Empty: coverage.lut beside the
  // LUT when it exists, else every node is trusted. `ignore_coverage` ignores coverage altogether.
  std::filesystem::path coverage;
  bool ignore_coverage = false;
  // Empty: W/lutex/restored.
  std::filesystem::path output;
  // How the input images are encoded (the default, 8-bit sRGB, is what cameras' JPEGs are).
  ImageEncoding input_encoding = ImageEncoding::kSrgb8;
  // "same" (as the input), "srgb8", "linear16" or "float" (EXR).
  std::string output_encoding = "same";
  RestorationOptions restoration;
  // The restored albedo smoothed where its noise is strong (lib/restoration/noise_adaptive_smoothing.h).
  NoiseAdaptiveSmoothingOptions smoothing;
  int num_threads = 0;
  // The stage refuses to start when its memory estimate (stage_memory.h) exceeds this; 0: the machine's
  // available memory.
  std::size_t memory_limit_bytes = 0;
  // Leave images alone whose restored image and confidence map both exist (lutex run resumes so; files
  // are written under temporary names and renamed, so an existing one is whole).
  bool skip_done = false;
  // An image that cannot be read (its header before the first write: size, channels, bit depth; or its
  // pixels mid-run) stops the command by default, naming it, with every output written so far complete.
  // With skip_bad_images it is skipped and listed in the summary instead.
  bool skip_bad_images = false;

  void Check() const;
};

struct RestoreSummary {
  std::filesystem::path output;
  std::filesystem::path coverage;  // the coverage LUT used; empty when none
  std::filesystem::path confidence_output;
  std::size_t num_images = 0;   // restored now
  std::size_t num_skipped = 0;  // already done (skip_done)
  std::vector<std::string> bad_images;  // "path: what is wrong", skipped (skip_bad_images)
  double mean_confidence = 0.0;  // over pixels with a surface, all channels, of the images restored now
  // Images divided by a gain other than 1 (the LUT's exposure.json: EXIF and fitted gains), and those
  // without the EXIF settings the LUT was calibrated with.
  std::size_t num_exposure_adjusted = 0;
  std::vector<std::string> missing_exif;
  double seconds = 0.0;
};

// Where RestoreWorkspace writes the restored image of the model's image `name`: OUTPUT/NAME, but .exr for
// float output and .png for 16-bit output whose name's extension cannot hold it (e.g. .jpg).
std::filesystem::path RestoredImagePath(const std::filesystem::path& output, const std::string& name,
                                        ImageEncoding encoding);

// The restored image of `name` in `folder`, whatever the output encoding was (as named, or renamed to .png
// or .exr as above); empty when there is none.
std::filesystem::path FindRestoredImage(const std::filesystem::path& folder, const std::string& name);

// Reads and validates the model, mesh, LUT and the existence of every image before writing anything.
RestoreSummary RestoreWorkspace(const RestoreOptions& options);
// The same on a dive loaded before (`lutex run` loads it once for every stage): `dive` holds the workspace
// and mesh of `options`.
RestoreSummary RestoreWorkspace(const RestoreOptions& options, const LoadedDive& dive);

// The lines the stage prints when done.
void PrintRestoreSummary(std::ostream& out, const RestoreSummary& summary);

}  // namespace lutex
