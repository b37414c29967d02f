#!/usr/bin/env bash
# Installs everything lutex needs to build and test on Debian 12 (bookworm): C++ libraries and tools from
# Debian's archive (Chromium renders lutex's HTML report and its GLB in tests; clang builds the libFuzzer
# targets of scripts/fuzz.sh), and from the npm registry the
# Khronos glTF-Validator (which checks lutex's GLB output), pinned by scripts/gltf_validator/package-lock.json,
# three.js (which renders the GLB in Chromium), pinned by scripts/threejs_viewer/package-lock.json, and
# CesiumJS (which renders the 3D Tiles in Chromium), pinned by scripts/cesium_viewer/package-lock.json.
# Idempotent: what is present is left as it is.
# Run as root (or through sudo).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libceres-dev
  libopencv-dev libopencv-contrib-dev
  libopenmesh-dev libembree-dev
  libtinygltf-dev nlohmann-json3-dev libstb-dev
  libgdal-dev libproj-dev gdal-bin
  libmeshoptimizer-dev
  libgoogle-perftools-dev
  libgtest-dev libgmock-dev
  clang libclang-rt-14-dev
  colmap
  python3-numpy python3-opencv python3-gdal
  chromium
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

# Node.js and npm for the glTF validator and three.js: the machine's own when present, else Debian's.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  missing+=(nodejs npm)
fi

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install_dependencies: all ${#packages[@]} packages already installed"
else
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  echo "install_dependencies: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

validator_dir="$(dirname "$0")/gltf_validator"
if [ ! -f "$validator_dir/node_modules/gltf-validator/package.json" ]; then
  echo "install_dependencies: installing the glTF validator (npm ci in $validator_dir)"
  npm ci --prefix "$validator_dir" --no-audit --no-fund --loglevel=error
fi

cesium_dir="$(dirname "$0")/cesium_viewer"
if [ ! -f "$cesium_dir/node_modules/cesium/package.json" ]; then
  echo "install_dependencies: installing CesiumJS (npm ci in $cesium_dir)"
  npm ci --prefix "$cesium_dir" --no-audit --no-fund --loglevel=error
fi

viewer_dir="$(dirname "$0")/threejs_viewer"
if [ ! -f "$viewer_dir/node_modules/three/package.json" ]; then
  echo "install_dependencies: installing three.js (npm ci in $viewer_dir)"
  npm ci --prefix "$viewer_dir" --no-audit --no-fund --loglevel=error
fi
