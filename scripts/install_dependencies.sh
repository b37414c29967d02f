#!/usr/bin/env bash
# Installs everything lutex needs to build and test on Debian 12 (bookworm), from Debian's archive only.
# Idempotent: packages already present are left as they are. Run as root (or through sudo).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libceres-dev
  libopencv-dev libopencv-contrib-dev
  libopenmesh-dev libembree-dev
  libtinygltf-dev nlohmann-json3-dev libstb-dev
  libgtest-dev libgmock-dev
  colmap
  python3-numpy python3-opencv
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install_dependencies: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "install_dependencies: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
