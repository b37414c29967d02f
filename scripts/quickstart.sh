#!/usr/bin/env bash
# The README's first command: installs the Debian packages lutex needs, builds lutex, simulates the bundled
# example (a small dive: two lights in clear water over a synthetic seafloor) and runs lutex on it:
# ray casting, restoration with the LUT the simulator knows is true, and a textured GLB.
# Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install_dependencies.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel 2

echo
build/lutex simulate --scene examples/scenes/clear_two_lights.json --output build/example
build/lutex raycast --workspace build/example --mesh build/example/scene/mesh.ply
build/lutex restore --workspace build/example --mesh build/example/scene/mesh.ply \
  --lut build/example/ground_truth/true.lut
build/lutex texture --workspace build/example --mesh build/example/scene/mesh.ply
