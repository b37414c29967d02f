#pragma once

#include <string>

#include "colmap_integration/cli/option_parser.h"
#include "lib/image/image_io.h"

namespace lutex {

// Registers `--NAME srgb8|linear16|float` on `parser`, parsed into *encoding; `help` says whose encoding it
// is ("How W's images are encoded:"), the choices and the default are appended.
void AddImageEncodingOption(OptionParser& parser, const std::string& name, ImageEncoding* encoding,
                            const std::string& help);

}  // namespace lutex
