#include "colmap_integration/cli/image_encoding_option.h"

namespace lutex {

void AddImageEncodingOption(OptionParser& parser, const std::string& name, ImageEncoding* encoding,
                            const std::string& help) {
  parser.AddCustom(name, ImageEncodingName(*encoding),
                   help + " srgb8 (8-bit sRGB, cameras' JPEGs), linear16 (16-bit linear PNG/TIFF) or float (EXR).",
                   [encoding](const std::string& text) { *encoding = ParseImageEncoding(text); });
}

}  // namespace lutex
