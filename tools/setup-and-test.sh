#!/usr/bin/env bash
# README command 2: set up, build, run the whole test suite through ctest, then bounded runs of
# the fuzzers: 60 s of the glTF loader's, 20 s of the options/TRAY_* one (clang + ASan/UBSan
# build in build-fuzz/; see docs/fuzzing.md). TRAY_SKIP_FUZZ=1 skips the fuzz runs.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
# The farm tests (ctest label farm) run a one-machine Slurm cluster as root: its packages too.
if [ "$(id -u)" -eq 0 ]; then
  export TRAY_EXTRA_PACKAGES="${TRAY_EXTRA_PACKAGES:-} slurmctld slurmd slurm-client munge"
fi
source tools/setup.sh
ctest --test-dir "$BUILD_DIR" --output-on-failure -j"$(nproc)" "$@"
if [ "${TRAY_SKIP_FUZZ:-0}" != 1 ]; then
  (unset BUILD_DIR TRAY_CMAKE_ARGS; tools/fuzz.sh "${TRAY_FUZZ_SECONDS:-60}" >build-fuzz.log 2>&1) ||
    { tail -40 build-fuzz.log; echo "fuzz run failed (log: build-fuzz.log)"; exit 1; }
  grep -E "stat::number_of_executed_units|stat::average_exec_per_sec" build-fuzz.log || true
  # The second target: command-line options and TRAY_* extensions (20 s).
  (unset BUILD_DIR TRAY_CMAKE_ARGS; TRAY_FUZZER=options_fuzz tools/fuzz.sh \
    "${TRAY_FUZZ_OPTIONS_SECONDS:-20}" >build-fuzz-options.log 2>&1) ||
    { tail -40 build-fuzz-options.log; echo "fuzz run failed (log: build-fuzz-options.log)"; exit 1; }
  grep -E "stat::number_of_executed_units|stat::average_exec_per_sec" build-fuzz-options.log || true
fi
