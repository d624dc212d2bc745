#!/bin/sh
# Memcheck over a few representative renders: a triangle-mesh scene through Embree with the path
# tracer (the Cornell box), CSG (user geometry, all-hits queries), textures (OIIO decoding) and
# the wavefront's glossy SIMD stage (DamagedHelmet) and its delta stage (TransmissionTest),
# each tiny and on one thread so the whole test takes well under two minutes. Any invalid read
# or write, use of uninitialised memory or bad free fails the test; leaks are not errors here
# (ASan's LeakSanitizer covers them, README "Hardened input").
# Usage: run.sh TRAY_RENDER SOURCE_DIR SHARED_DIR. Exit 77 (ctest SKIP_RETURN_CODE): no valgrind.
set -u
render=$1 src=$2 shared=$3
command -v valgrind >/dev/null 2>&1 || { echo "valgrind not installed: skipped"; exit 77; }
out=$(mktemp -d "${TMPDIR:-/tmp}/tray_valgrind.XXXXXX")
# Removed when the test passes; kept, and named, when it fails.
keep_if_failed() {
  if [ $? -eq 0 ]; then rm -rf "$out"; else echo "test files kept in $out" >&2; fi
}
trap keep_if_failed EXIT
status=0
check() {  # check NAME SCENE ARGS...
  name=$1 scene=$2
  shift 2
  if [ ! -f "$scene" ]; then echo "$name: $scene missing: not checked"; return; fi
  start=$(date +%s)
  valgrind --error-exitcode=9 --errors-for-leak-kinds=none --log-file="$out/$name.log" \
    "$render" "$scene" --resolution 32x24 --threads 1 -q -o "$out/$name.exr" "$@"
  rc=$?
  echo "$name: exit $rc, $(grep -h 'ERROR SUMMARY' "$out/$name.log" | sed 's/^==[0-9]*== //')," \
    "$(($(date +%s) - start)) s"
  if [ "$rc" -ne 0 ]; then
    cat "$out/$name.log"
    status=1
  fi
}
check cornell-path "$shared/reference/cornell-box.gltf" --integrator path --spp 2
# Embree's 8-wide packets: inactive lanes were uninitialised (66 errors before they were zeroed).
check cornell-wavefront "$shared/reference/cornell-box.gltf" --integrator path-wavefront --spp 2
# Renders in passes (docs/adaptive-sampling.md): the pass renderer, its checkpoints and samples AOV.
check cornell-adaptive "$shared/reference/cornell-box.gltf" --integrator path --spp 8 \
  --min-spp 2 --noise-threshold 0.1 --aov samples --checkpoint 0.01
check csg "$src/scenes/csg.gltf"
check textured "$src/scenes/textured.gltf"
# The wavefront's glossy SIMD stage (textured metal and plastic): its light sample, inlined whole,
# was once one block more than memcheck can instrument ("VEX temporary storage exhausted").
check glossy-stage "$shared/gltf-samples/DamagedHelmet.glb" --integrator path --spp 1
# The delta stage (smooth glass) and the punctual lights' gathers (the default key light).
check delta-stage "$shared/gltf-samples/TransmissionTest.glb" --integrator path --spp 1
# The hair BSDF on Embree's curves (scalar code): a member the merge of two lobes left unset on
# the hair path was read uninitialised (1202 errors) until it was set.
check hair "$src/scenes/curves/fur_patch.gltf" --integrator path --spp 1
# Instance arrays (docs/instancing.md): forced on the small sample by a threshold of 1, through
# Embree's user-geometry callbacks and the in-house BVH's array leaves.
check instance-array "$src/scenes/instancing.gltf" --integrator path --spp 1 --instance-arrays 1
check instance-array-bvh "$src/scenes/instancing.gltf" --integrator path --spp 1 \
  --instance-arrays 1 --accel bvh
exit $status
