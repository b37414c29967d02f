#!/usr/bin/env bash
# The README's first command: installs the Debian packages lutex needs, builds lutex, simulates the bundled
# example (a small dive: two lights in clear water over a synthetic seafloor, plus frames of a colour board
# and of open water taken with the same rig) and runs `lutex run` on it: calibration from the board and the
# pure water, restoration, a textured GLB and an HTML report.
# Safe to run again: the example is simulated once, and lutex run skips what is up to date.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install_dependencies.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel 2

echo
example=build/example
simulate() {  # scene, workspace
  if [ ! -d "$2/sparse" ]; then build/lutex simulate --scene "$1" --output "$2"; fi
}
simulate examples/scenes/clear_two_lights.json "$example/survey"
simulate examples/dive/board.json "$example/board"
simulate examples/dive/purewater.json "$example/purewater"
build/lutex run --workspace "$example/survey" --mesh "$example/survey/scene/mesh.ply" \
  --targets examples/dive/board_targets.json \
  --targets-workspace "$example/board" --targets-mesh "$example/board/scene/mesh.ply" \
  --pure-water "$example/purewater"
