#!/usr/bin/env bash
# Renders every shared glTF sample (../shared/gltf-samples, ../shared/gltf-features; not the
# hostile files in invalid/) with the path tracer into docs/gallery/NAME.png, then a contact
# sheet docs/gallery/contact.png and a README listing it, so a person can look at what TRay
# makes of real assets (issue 15).
#   tools/render-gallery.sh [SIZE=128] [SPP=16] [BUILD=build]
# Animated assets are rendered at --time 1 (skins and morphs posed); the rest as they are.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
size=${1:-128} spp=${2:-16} build=${3:-build}
shared=${TRAY_SHARED_DIR:-../shared}
out=docs/gallery
mkdir -p "$out"
rm -f "$out"/*.png "$out"/*.log
failed=0
tiles=()
for f in "$shared"/gltf-samples/*.gl* "$shared"/gltf-samples/*/*.gltf \
         "$shared"/gltf-features/*.gl* "$shared"/gltf-features/*/*.gltf; do
  [ -f "$f" ] || continue
  case "$f" in */invalid/*) continue ;; esac  # hostile files: tests/cli/invalid_scenes_test.cpp
  name=$(basename "${f%.*}")
  extra=()
  case "$name" in
    CesiumMan | RiggedFigure | RiggedSimple | SimpleSkin | BoxAnimated | AnimatedCube | \
      AnimatedMorphCube | SimpleMorph | InterpolationTest) extra=(--time 1) ;;
  esac
  if "$build/tray-render" -q --integrator path --spp "$spp" --resolution "${size}x${size}" \
    "${extra[@]}" "$f" -o "$out/$name.png" 2>"$out/$name.log"; then
    tiles+=("$out/$name.png")
    rm -f "$out/$name.log"
  else
    echo "render-gallery: $name failed: $(head -1 "$out/$name.log")" >&2
    failed=$((failed + 1))
  fi
done

# The contact sheet, 6 across, in the order the README lists (this OIIO build has no font for
# --text, so the names are listed rather than drawn).
cols=6
rows=$(((${#tiles[@]} + cols - 1) / cols))
sheet=("${tiles[@]}")
oiiotool --create "${size}x${size}" 3 -o "$out/blank.tmp.png"
while ((${#sheet[@]} < cols * rows)); do sheet+=("$out/blank.tmp.png"); done
oiiotool "${sheet[@]}" --mosaic:pad=2 "${cols}x${rows}" -o "$out/contact.png"
rm -f "$out/blank.tmp.png"
{
  echo "# Gallery: every shared sample, as TRay renders it"
  echo
  echo "\`tools/render-gallery.sh $size $spp\`: path tracer, $spp spp, ${size}×${size}, the default"
  echo "camera and lighting (animated assets at \`--time 1\`). [contact.png](contact.png) shows them"
  echo "left to right, top to bottom, in this order:"
  echo
  i=0
  for t in "${tiles[@]}"; do
    i=$((i + 1))
    echo "$i. [$(basename "${t%.png}")]($(basename "$t"))"
  done
} >"$out/README.md"
echo "render-gallery: ${#tiles[@]} assets in $out ($failed failed), contact sheet $out/contact.png"
exit $((failed > 0))
