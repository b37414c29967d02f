// Option files of `--config FILE` (colmap_integration/cli/option_parser.h): a parser with an option of every
// kind the commands use (paths, required ones, whole numbers with and without a range, numbers, text, flags
// and their no- form, an image encoding, the log level) reads the input as its config file. The parser's
// sources are compiled into this target (fuzz/CMakeLists.txt) so that the stages need not be built.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "colmap_integration/cli/dive_options.h"
#include "colmap_integration/cli/image_encoding_option.h"
#include "colmap_integration/cli/option_parser.h"
#include "fuzz/fuzz_input.h"
#include "lib/util/logging.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = lutex::WriteFuzzFile("lutex.conf", lutex::FuzzBytes(data, size));
  lutex::OptionParser parser("lutex fuzz --workspace W --mesh M [options]", "The config file fuzz target.");
  std::filesystem::path workspace, mesh, targets;
  int num_threads = 0, lut_nx = 40, tile_size = 256;
  double z_far = 5.0;
  std::string crs;
  bool correspondences = false;
  lutex::ImageEncoding encoding = lutex::ImageEncoding::kSrgb8;
  lutex::AddDiveOptions(parser, &workspace, &mesh);
  lutex::AddThreadsOption(parser, &num_threads);
  parser.SetGroup("calibrate");
  parser.AddPath("targets", &targets, "Targets file.");
  parser.AddInt("lut-nx", &lut_nx, "LUT cells across.");
  parser.AddDouble("z-far", &z_far, "Far end of the LUT (m).");
  parser.AddFlag("correspondences", &correspondences, "Self-calibration from the survey.");
  parser.SetGroup("mosaic");
  parser.AddIntInRange("tile-size", &tile_size, 16, 8192, "Tile side (px).");
  parser.AddString("crs", &crs, "Map CRS.");
  lutex::AddImageEncodingOption(parser, "encoding", &encoding, "The output's encoding:");
  const std::string config = "--config=" + path.string();
  char* argv[] = {const_cast<char*>("lutex"), const_cast<char*>("run"), const_cast<char*>(config.c_str())};
  try {
    if (parser.Parse(3, argv, 2)) {
      parser.Settings("calibrate");
      parser.Settings("mosaic");
    }
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  lutex::SetLogLevel(lutex::LogLevel::kSilent);  // the file may have set it
  return 0;
}
