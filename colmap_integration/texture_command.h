#pragma once

namespace lutex {

// `lutex texture`: parses the options and calls TextureWorkspace (texture_workspace.h).
int RunTextureCommand(int argc, char** argv);

}  // namespace lutex
