#!/usr/bin/env bash
# Installs the build into a temporary prefix, moves away from the source tree and renders with
# the installed tray-render: the OCIO config must come from PREFIX/share/tray (an ACEScg EXR and
# an sRGB PNG need it), tray-merge and tray-farm must run, and no installed file may name the source folder.
set -euo pipefail
build=$1 source=$2
prefix=$(mktemp -d)
# Removed when the test passes; kept, and named, when it fails.
keep_if_failed() {
  if [ $? -eq 0 ]; then rm -rf "$prefix"; else echo "test files kept in $prefix" >&2; fi
}
trap keep_if_failed EXIT
cmake --install "$build" --prefix "$prefix" >/dev/null
test -x "$prefix/bin/tray-render" && test -x "$prefix/bin/tray-merge"
test -f "$prefix/share/tray/ocio/config.ocio"
cp "$source/scenes/whitted.gltf" "$prefix/"
cd "$prefix"
env -u OCIO "$prefix/bin/tray-render" -q whitted.gltf --resolution 32x24 --output-colorspace ACEScg \
  -o out.exr -o out.png
test -s out.exr && test -s out.png
"$prefix/bin/tray-merge" --help >/dev/null
# tray-farm finds its modules in share/tray/farm and tray-render beside itself. grep reads all
# (not -q): quitting at the first match could break tray-farm's pipe, failing under pipefail.
"$prefix/bin/tray-farm" submit whitted.gltf --split regions:2 --resolution 32x24 -o farm.exr \
  --dry-run | grep -F "exec $prefix/bin/tray-render " >/dev/null
if grep -rlF "$source" "$prefix/bin" "$prefix/share"; then
  echo "installed files name the source folder $source" >&2
  exit 1
fi
echo "installed to $prefix: rendered with share/tray/ocio, no source paths"
