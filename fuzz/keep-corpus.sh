#!/usr/bin/env bash
# Keeps what a fuzz campaign learnt: merges the inputs of WORKDIR/corpus that add coverage into
# the corpus committed in fuzz/corpus/NAME (libFuzzer -merge=1), small ones only (<= 8 KiB), so
# the next campaign, here or in CI, starts where this one stopped (docs/fuzzing.md).
#   fuzz/keep-corpus.sh FUZZER WORKDIR NAME     e.g. build-fuzz/gltf_loader_fuzz build-fuzz/gltf_loader_fuzz-work gltf
set -euo pipefail
fuzzer=$1 work=$2 name=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
keep="$here/corpus/$name"
small=$(mktemp -d)
trap 'rm -rf "$small"' EXIT
mkdir -p "$keep"
# Only what libFuzzer generated (named by their SHA-1): seeds copied from ../shared keep their
# names and stay out, as they are not ours to commit.
find "$work/corpus" -type f -size -9k -regextype posix-extended -regex ".*/[0-9a-f]{40}" \
  -exec cp -t "$small" {} +
export ASAN_OPTIONS=detect_leaks=0
export LSAN_OPTIONS=suppressions=$here/../tools/lsan.supp:print_suppressions=0
"$fuzzer" -merge=1 -timeout=10 -rss_limit_mb=2048 "$keep" "$small" 2>&1 | grep -E "MERGE-OUTER: [0-9]+ new files" || true
echo "$(ls "$keep" | wc -l) files in $keep ($(du -sh "$keep" | cut -f1))"
