#!/usr/bin/env bash
# Installs TRay's missing Debian packages (as root) and builds it (Release) into build/.
# Sourced by the README's two commands; safe to run again (installs and rebuilds only what changed).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

PACKAGES=(libembree-dev libopenimageio-dev openimageio-tools libopenexr-dev libopencolorio-dev
  opencolorio-tools libtinygltf-dev nlohmann-json3-dev libstb-dev libtbb-dev libgtest-dev
  libbenchmark-dev libcli11-dev libxxhash-dev libhwy-dev cmake ninja-build g++ pkg-config python3 valgrind
  python3-openimageio python3-numpy python3-venv
  pybind11-dev python3-pybind11 python3-dev python3-pytest libcpp-httplib-dev
  chromium python3-websocket)
PACKAGES+=(${TRAY_EXTRA_PACKAGES:-})

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

BUILD_DIR=${BUILD_DIR:-build}
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release ${TRAY_CMAKE_ARGS:-} >/dev/null
cmake --build "$BUILD_DIR" -j"$(nproc)"
# The denoiser (tools/tray-denoise) is optional: the renderer and its tests run without it.
tools/setup-denoise.sh ||
  echo "setup: pyoidn could not be installed: tray-denoise (and its test) will be skipped"
