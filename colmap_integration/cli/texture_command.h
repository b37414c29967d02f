#pragma once

// `lutex texture`, and the baking options `lutex run` and `lutex mosaic` share.

#include <string>

#include "colmap_integration/cli/option_parser.h"
#include "colmap_integration/stages/texture_workspace.h"

namespace lutex {

// `lutex texture`: parses the options and calls TextureWorkspace (texture_workspace.h).
int RunTextureCommand(int argc, char** argv);

// Registers how to bake: the options of `lutex texture` except --workspace, --mesh, --images,
// --image-encoding, --confidence, --output, --page-encoding and --num-threads (which `lutex run` sets).
void AddTextureStageOptions(OptionParser& parser, TextureOptions* options);

// The same for any baking stage (texture, tiles): how to bake, whether to trust the confidence maps, and
// the model's up.
// --meshopt-compression.
void AddGltfOptions(OptionParser& parser, GltfOptions* gltf);

void AddBakingOptions(OptionParser& parser, TextureBakingOptions* baking, bool* ignore_confidence, std::string* up_axis);

// Registers how views are chosen and fused (--blend, --view-smoothness, --max-views-per-face): the
// texture's, which the mosaic shares.
void AddViewFusionOptions(OptionParser& parser, TextureBakingOptions* baking);

}  // namespace lutex
