#include "colmap_integration/cli/restore_command.h"

#include <iomanip>
#include <iostream>

#include "colmap_integration/cli/dive_options.h"
#include "colmap_integration/cli/image_encoding_option.h"

namespace lutex {

int RunRestoreCommand(int argc, char** argv) {
  RestoreOptions options;
  OptionParser parser(
      "lutex restore --workspace W --mesh M --lut L [--output DIR] [--input-encoding E] [--output-encoding E]",
      "Restores every registered image of the COLMAP workspace W to albedo with the LUT L (lutex calibrate):\n"
      "per pixel, the mesh gives the surface point and its shading cos_theta, the LUT gives alpha and beta,\n"
      "and albedo = (I - beta) / (alpha cos_theta); when the LUT records forward scattering (calibrate takes it\n"
      "out by default), the same is first taken out of the image. Writes DIR/NAME (default DIR:\n"
      "W/lutex/restored) and an 8-bit confidence map DIR_confidence/NAME.png per image (255 = fully\n"
      "trusted; low where the signal is weak, the pixel saturated, the surface seen at a grazing angle, or\n"
      "the LUT there not constrained by calibration data). Pixels without a surface are 0.\n"
      "Input encoding: srgb8 (8-bit sRGB, cameras' JPEGs; the default), linear16 (16-bit linear PNG/TIFF) or\n"
      "float (EXR). Output encoding: same (as the input; the default), srgb8, linear16 or float.");
  AddDiveOptions(parser, &options.workspace, &options.mesh);
  parser.AddPath("lut", &options.lut, "Calibrated LUT file.", true);
  parser.AddPath("coverage", &options.coverage,
                 "Per-node coverage of the LUT (default: coverage.lut beside the LUT, when present).");
  parser.AddPath("output", &options.output, "Output folder (default W/lutex/restored).");
  AddImageEncodingOption(parser, "input-encoding", &options.input_encoding, "How W's images are encoded:");
  AddThreadsOption(parser, &options.num_threads);
  AddMemoryLimitOption(parser, &options.memory_limit_bytes);
  AddRestoreStageOptions(parser, &options);
  if (!parser.Parse(argc, argv, 2)) return 0;
  parser.RunWithFlags([&] {
    PrintRestoreSummary(std::cout, RestoreWorkspace(options));
  });
  return 0;
}

void AddRestoreStageOptions(OptionParser& parser, RestoreOptions* options) {
  parser.AddFlag("skip-bad-images", &options->skip_bad_images,
                 "Skip images that cannot be read (wrong size or depth, corrupt, truncated) and list them;\n"
                 "      without it the first one stops restore, naming it, before anything is written where\n"
                 "      its header shows the fault.");
  parser.AddFlag("no-coverage", &options->ignore_coverage, "Ignore the LUT's coverage in the confidence maps.");
  parser.AddFlag("smooth-noise", &options->smoothing.enabled,
                 "Smooth the restored albedo where restoration amplified the noise (far, dark, outside the\n"
                 "      beams, red in turbid water), as strongly as the noise each image shows, without\n"
                 "      blurring edges or detail above the noise (README, 'Noise'). --no-smooth-noise keeps\n"
                 "      every pixel's own value.");
  parser.AddIntInRange("smooth-noise-passes", &options->smoothing.passes, 1, 16,
                "Times the smoothing runs, each on the last one's result with its noise measured again:\n"
                "      more passes average more of the noise left where it is strong, and change\n"
                "      next to nothing where none is left; each costs about a fifth of restore's time.");
  parser.AddString("output-encoding", &options->output_encoding, "Restored images: same (as the input), srgb8, linear16 or float.");
}

}  // namespace lutex
