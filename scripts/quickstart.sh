#!/usr/bin/env bash
# The README's first command: installs the Debian packages lutex needs, builds lutex, makes the bundled
# example (a small synthetic survey) and runs the main job on it. Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install_dependencies.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel 2

echo
build/examples/make_example_workspace build/example
build/lutex raycast --workspace build/example --mesh build/example/seafloor.ply
