#!/usr/bin/env bash
# Builds the libFuzzer target with Debian's clang into build-fuzz/ and runs it (docs/fuzzing.md):
#   [TRAY_FUZZER=options_fuzz] tools/fuzz.sh [SECONDS] [extra libFuzzer flags, e.g. -jobs=2]
# The Python module is not built there: an ASan+LTO shared module with sancov counters does
# not link (lld drops the counters' constructors), and nothing fuzzes it.
# Installs clang and libclang-rt through setup.sh's TRAY_EXTRA_PACKAGES; the normal build and
# CI need neither.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
seconds=${1:-60}
shift $(($# < 1 ? $# : 1))
# CXX picks clang when build-fuzz/ is first configured (later runs keep the cached compiler).
CXX=clang++ TRAY_EXTRA_PACKAGES="clang libclang-rt-14-dev ${TRAY_EXTRA_PACKAGES:-}" BUILD_DIR=build-fuzz \
  TRAY_CMAKE_ARGS="-DTRAY_BUILD_FUZZ=ON \
    -DTRAY_BUILD_TESTS=OFF -DTRAY_BUILD_BENCH=OFF -DTRAY_BUILD_PYTHON=OFF ${TRAY_CMAKE_ARGS:-}" tools/setup.sh
# TRAY_FUZZER=options_fuzz fuzzes the command-line options and TRAY_* extensions instead.
fuzzer=${TRAY_FUZZER:-gltf_loader_fuzz}
exec fuzz/run.sh "build-fuzz/$fuzzer" "build-fuzz/$fuzzer-work" "$seconds" "$@"
