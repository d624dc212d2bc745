#!/usr/bin/env bash
# Runs a fuzzer for a bounded time (docs/fuzzing.md):
#   fuzz/run.sh FUZZER WORKDIR [SECONDS] [extra libFuzzer flags...]
# gltf_loader_fuzz: first replays every committed reproducer in fuzz/regressions/, then fuzzes
# from a seed corpus copied fresh from ../shared/gltf-samples and scenes/ (never committed: the
# samples are large) plus the corpus kept in fuzz/corpus/gltf. options_fuzz: seeds and corpus in
# fuzz/corpus/options. New inputs the run finds stay in WORKDIR/corpus; `fuzz/keep-corpus.sh`
# merges the interesting small ones back into fuzz/corpus/.
# Crashes, leaks, timeouts and out-of-memory inputs land in WORKDIR/findings/; exit status is
# libFuzzer's (0: nothing found).
set -euo pipefail
fuzzer=$1 work=$2 seconds=${3:-60}
shift $(($# < 3 ? $# : 3))
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
shared=${TRAY_SHARED_DIR:-$here/../../shared}

mkdir -p "$work/corpus" "$work/findings"
if [ "$(basename "$fuzzer")" = options_fuzz ]; then
  cp -n "$here"/corpus/options/* "$work/corpus/" 2>/dev/null || true
  export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
  exec "$fuzzer" "$work/corpus" -dict="$here/options.dict" -max_total_time="$seconds" \
    -max_len=4096 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$work/findings/" "$@"
fi
# Seeds: every .gltf/.glb up to 512 KiB (larger ones slow each execution more than they add).
find "$shared/gltf-samples" "$here/../scenes" "$here/regressions" -type f \
  \( -name '*.gltf' -o -name '*.glb' -o -path '*/regressions/*' \) -size -513k \
  -exec cp -n -t "$work/corpus" {} + 2>/dev/null || true
cp -n "$here"/corpus/gltf/* "$work/corpus/" 2>/dev/null || true

# OIIO/libpng leak on corrupt PNGs (tools/lsan.supp says why); everything else must not leak.
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$here/../tools/lsan.supp:print_suppressions=0}
# Regression inputs alone first: a fixed bug that comes back fails here in seconds.
regressions=("$here"/regressions/*)
if [ -e "${regressions[0]}" ]; then
  "$fuzzer" -rss_limit_mb=2048 -timeout=10 "${regressions[@]}" >"$work/regressions.log" 2>&1 ||
    { tail -40 "$work/regressions.log"; exit 1; }
fi

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
exec "$fuzzer" "$work/corpus" -dict="$here/gltf.dict" -max_total_time="$seconds" \
  -max_len=524288 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$work/findings/" "$@"
