#!/usr/bin/env bash
# README command 1: set up, build, render the default scene to out/whitted.exr and out/whitted.png.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source tools/setup.sh
mkdir -p out
"$BUILD_DIR/tray-render" --integrator=whitted scenes/whitted.gltf -o out/whitted.exr -o out/whitted.png "$@"
