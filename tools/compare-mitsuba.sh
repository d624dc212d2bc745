#!/bin/sh
# TRay's path tracer against Mitsuba 3 measured in the same run (bench/mitsuba_compare.py): the
# Cornell box and the heavier scenes/bench/heavy-*.gltf; report in docs/bench/mitsuba-compare.txt, the
# converged heavier scenes side by side in docs/bench/mitsuba-heavy-side-by-side.png. Needs
# build/path_bench and build/tray-render:
#   cmake --build build --target path_bench tray-render
# Extra arguments go to the script (e.g. --quick, --no-cornell, --tray-build DIR).
set -eu
cd "$(dirname "$0")/.."
sh tools/setup-mitsuba.sh
export DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1
mkdir -p docs/bench
exec build/mitsuba-venv/bin/python bench/mitsuba_compare.py \
  --report docs/bench/mitsuba-compare.txt \
  --side-by-side docs/bench/mitsuba-heavy-side-by-side.png "$@"
