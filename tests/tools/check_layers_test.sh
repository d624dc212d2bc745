#!/usr/bin/env bash
# tools/check_layers.py passes on the real tree and fails, naming the file and line, on a copy
# with one deliberate wrong include (core/ including integrators/), as the build would; and on
# one spelled with angle brackets (film/ including <render/...>).
set -euo pipefail
source=$1
python3 "$source/tools/check_layers.py" "$source"
tree=$(mktemp -d)
# Removed when the test passes; kept, and named, when it fails.
keep_if_failed() {
  if [ $? -eq 0 ]; then rm -rf "$tree"; else echo "test files kept in $tree" >&2; fi
}
trap keep_if_failed EXIT
for d in core textures film shapes accel materials lights integrators io gltf render cli; do cp -r "$source/$d" "$tree/"; done
# Appends `include` to `file` in the copy and expects the check to refuse it with a message
# matching `says`; then restores the file.
expect_refused() {
  local file=$1 include=$2 says=$3 out
  printf '%s\n' "$include" >>"$tree/$file"
  if out=$(python3 "$source/tools/check_layers.py" "$tree" 2>&1); then
    echo "a wrong include passed the layer check: $include in $file" >&2
    exit 1
  fi
  grep -q "$says" <<<"$out" || {
    echo "unexpected message: $out" >&2
    exit 1
  }
  echo "wrong include refused: $out"
  cp "$source/$file" "$tree/$file"
}
expect_refused core/scene.h '#include "integrators/registry.h"' \
  "core/scene.h:.*layer 'core' includes 'integrators/'"
# The same with <...>: a project header in angle brackets is still a layer's.
expect_refused film/film.h '#include <render/render_job.h>' \
  "film/film.h:.*layer 'film' includes 'render/'"
