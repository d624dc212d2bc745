#!/bin/sh
# TRay's path tracer against Mitsuba 3 measured in the same run (bench/mitsuba_compare.py),
# report in docs/bench/mitsuba-compare.txt. Needs build/path_bench and build/tray-render:
#   cmake --build build --target path_bench tray-render
# Extra arguments go to the script (e.g. --repeats 1 --size 256).
set -eu
cd "$(dirname "$0")/.."
sh tools/setup-mitsuba.sh
export DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1
mkdir -p docs/bench
exec build/mitsuba-venv/bin/python bench/mitsuba_compare.py \
  --report docs/bench/mitsuba-compare.txt "$@"
