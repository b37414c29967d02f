#pragma once

// `lutex mosaic`: the georeferenced orthomosaic and DEM as Cloud-Optimized GeoTIFFs.

#include "colmap_integration/cli/option_parser.h"
#include "colmap_integration/stages/mosaic_workspace.h"

namespace lutex {

// Parses the options and calls MosaicWorkspace (mosaic_workspace.h).
int RunMosaicCommand(int argc, char** argv);

// Registers --gsd, the georeference and --tile-size: the options `lutex run` shares.
void AddMosaicStageOptions(OptionParser& parser, MosaicOptions* options);

// Registers --crs, --crs-origin and --enu-origin.
void AddGeoreferenceOptions(OptionParser& parser, GeoreferenceOptions* georeference);

}  // namespace lutex
