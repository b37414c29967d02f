#pragma once

// `lutex mesh`: a surface from a sparse COLMAP model.

#include "colmap_integration/cli/option_parser.h"
#include "colmap_integration/stages/mesh_workspace.h"

namespace lutex {

// Parses the options and calls MeshWorkspace (mesh_workspace.h).
int RunMeshCommand(int argc, char** argv);

// Registers how the surface is made (--resolution, --min-track-length, ...): the options `lutex run` shares.
void AddMeshStageOptions(OptionParser& parser, MeshOptions* options);

}  // namespace lutex
