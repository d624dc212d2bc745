#!/usr/bin/env bash
# Writes docs/options.md, tray-render's option reference, from the binary's own option
# declarations (tray-render --help-markdown; cli/options_doc.cpp). Never edit docs/options.md
# by hand: change an option's declaration, rebuild, run this.
#   tools/gen-options-doc.sh [BUILD=build]           rewrite docs/options.md
#   tools/gen-options-doc.sh --check [BUILD=build]   exit 1, with the difference, when
#                                                     docs/options.md is not what it would write
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
check=0
if [ "${1:-}" = --check ]; then check=1 && shift; fi
build=${1:-build}
doc=docs/options.md
new=$("$build/tray-render" --help-markdown)
if [ "$check" = 0 ]; then
  printf '%s\n' "$new" >"$doc"
  echo "wrote $doc"
  exit 0
fi
if ! diff -u "$doc" <(printf '%s\n' "$new") >&2; then
  echo "FAIL: $doc is not what tray-render --help-markdown prints now (an option was added or" \
    "changed without regenerating it): run tools/gen-options-doc.sh $build and commit $doc" >&2
  exit 1
fi
echo "$doc is up to date"
