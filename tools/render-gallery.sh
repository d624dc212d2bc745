#!/usr/bin/env bash
# Renders every shared glTF sample (../shared/gltf-samples, ../shared/gltf-features; not the
# hostile files in invalid/) with the path tracer at its defaults into docs/gallery/NAME.png and,
# given an HDR map, under that map into docs/gallery/NAME-env.png; then contact sheets and a
# README whose table puts each asset's two renders beside the verdict a person gave on looking
# at them (docs/gallery/verdicts.tsv: NAME, verdict, the difference named), with the counts
# (issues 15 and 39).
#   tools/render-gallery.sh [SIZE=128] [SPP=16] [BUILD=build] [MAP]
# MAP defaults to $TRAY_GALLERY_ENV, else Blender's courtyard.exr when tools/setup-blender.sh
# installed Blender 5.2 in build/cycles5-venv; without one the map column is left out.
# Animated assets are rendered at --time 1 (skins and morphs posed); the rest as they are.
# TRAY_GALLERY_README_ONLY=1 rewrites the README and contact sheets from the renders there (after
# editing verdicts or re-rendering one asset).
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
size=${1:-128} spp=${2:-16} build=${3:-build}
map=${4:-${TRAY_GALLERY_ENV:-}}
if [ -z "$map" ]; then
  map=$(ls build/cycles5-venv/lib/python3*/site-packages/bpy/*/datafiles/studiolights/world/courtyard.exr 2>/dev/null | head -1)
fi
shared=${TRAY_SHARED_DIR:-../shared}
out=docs/gallery
verdicts=$out/verdicts.tsv
mkdir -p "$out"
readmeOnly=${TRAY_GALLERY_README_ONLY:-0}
[ "$readmeOnly" = 1 ] || rm -f "$out"/*.png "$out"/*.log
failed=0
names=()
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
  render() {  # OUTPUT [options...]
    local png=$1
    shift
    "$build/tray-render" -q --integrator path --spp "$spp" --resolution "${size}x${size}" \
      "${extra[@]}" "$@" "$f" -o "$png" 2>"${png%.png}.log"
  }
  if [ "$readmeOnly" = 1 ]; then
    [ -f "$out/$name.png" ] && names+=("$name")
    continue
  fi
  if render "$out/$name.png" && { [ -z "$map" ] || render "$out/$name-env.png" --env "$map"; }; then
    names+=("$name")
    rm -f "$out/$name.log" "$out/$name-env.log"
  else
    echo "render-gallery: $name failed: $(cat "$out/$name.log" "$out/$name-env.log" 2>/dev/null | grep -m1 error)" >&2
    failed=$((failed + 1))
  fi
done

# Contact sheets, 6 across, in the README's order (this OIIO build has no font for --text, so
# the names are listed rather than drawn).
sheet() {  # OUTPUT SUFFIX
  local cols=6 tiles=()
  for n in "${names[@]}"; do tiles+=("$out/$n$2.png"); done
  local rows=$(((${#tiles[@]} + cols - 1) / cols))
  oiiotool --create "${size}x${size}" 3 -o "$out/blank.tmp.png"
  while ((${#tiles[@]} < cols * rows)); do tiles+=("$out/blank.tmp.png"); done
  oiiotool "${tiles[@]}" --mosaic:pad=2 "${cols}x${rows}" -o "$1"
  rm -f "$out/blank.tmp.png"
}
sheet "$out/contact.png" ""
[ -n "$map" ] && [ -f "$out/${names[0]}-env.png" ] && sheet "$out/contact-env.png" "-env"

verdict() {  # NAME -> "verdict<TAB>note", or not judged
  local line
  line=$(awk -F'\t' -v n="$1" '$1 == n {print $2 "\t" $3}' "$verdicts" 2>/dev/null)
  echo "${line:-not judged	}"
}
authored=0 named=0 wrong=0 unjudged=0
for n in "${names[@]}"; do
  case "$(verdict "$n" | cut -f1)" in
    "as authored") authored=$((authored + 1)) ;;
    difference) named=$((named + 1)) ;;
    wrong) wrong=$((wrong + 1)) ;;
    *) unjudged=$((unjudged + 1)) ;;
  esac
done
{
  echo "# Gallery: every shared sample, as TRay renders it"
  echo
  echo "\`tools/render-gallery.sh $size $spp\`: path tracer, $spp spp, ${size}×${size}, the default"
  echo "camera (animated assets at \`--time 1\`); first at the defaults (the file's lights, else"
  echo "TRay's default light), then under an HDR map (\`--env $(basename "${map:-none}")\`)."
  echo "Contact sheets: [defaults](contact.png), [under the map](contact-env.png). The verdicts"
  echo "are a person's, from looking at both renders beside what the asset is known to look like"
  echo "(\`docs/gallery/verdicts.tsv\`; the script only counts them). Scope: the samples in"
  echo "\`../shared\`; the whole Khronos sample set, each model beside its own screenshot, is"
  echo "[khronos/](khronos/README.md) (\`tools/khronos_gallery.py\`)."
  echo
  echo "**${#names[@]} assets: $authored rendered as authored, $named with a named difference,"
  echo "$wrong wrong, $unjudged not judged; $failed failed to render.**"
  echo
  echo "| # | asset | defaults | under the map | verdict | difference |"
  echo "|---|---|---|---|---|---|"
  i=0
  for n in "${names[@]}"; do
    i=$((i + 1))
    IFS=$'\t' read -r v note <<<"$(verdict "$n")"
    envcell="—"
    [ -n "$map" ] && envcell="![]($n-env.png)"
    echo "| $i | $n | ![]($n.png) | $envcell | $v | ${note:-} |"
  done
} >"$out/README.md"
echo "render-gallery: ${#names[@]} assets in $out ($failed failed): $authored as authored," \
  "$named named differences, $wrong wrong, $unjudged not judged"
exit $((failed > 0))
