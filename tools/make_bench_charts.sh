#!/usr/bin/env bash
# Regenerates docs/bench/: speed-against-accuracy sweeps (tray-bench) of the scenes in scenes/
# and of the Cornell box, their CSV, error-vs-time charts and Pareto reports (plot_bench.py).
# Modest settings (160x120, at most 256 spp); measured: 13 minutes on 2 busy shared cores,
# references included (rendered once, then cached):
#   tools/make_bench_charts.sh [BUILD_DIR]      (default: build; needs python3-matplotlib)
#   ONLY="csg cornell-box" tools/make_bench_charts.sh     (a subset of: whitted csg cornell-box)
# References are rendered by TRay and cached in $BENCH_CACHE (default: build/bench-cache), except
# the Cornell box's, Mitsuba 3's converged render from ../shared/reference.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
cache="${BENCH_CACHE:-$build/bench-cache}"
out="$here/docs/bench"
shared="${TRAY_SHARED_DIR:-$here/../shared}"
bench="$build/tray-bench"
# Debian's python3 has python3-matplotlib; a python3 earlier on PATH (pyenv, venv) may not.
py="${PYTHON:-$([ -x /usr/bin/python3 ] && echo /usr/bin/python3 || echo python3)}"
only="${ONLY:-whitted csg cornell-box}"
[ -x "$bench" ] || { echo "make_bench_charts: $bench missing (cmake --build $build --target tray-bench)" >&2; exit 2; }
mkdir -p "$out" "$cache"

sweep() {  # sweep NAME SCENE [tray-bench options...]
  local name="$1" scene="$2"
  shift 2
  case " $only " in *" $name "*) ;; *) return 0 ;; esac
  "$bench" sweep "$scene" --out "$cache/$name" "$@"
  cp "$cache/$name/$(basename "${scene%.*}").csv" "$out/$name.csv"
  "$py" "$here/tools/plot_bench.py" "$out/$name.csv" --out-dir "$out"
}

# Whitted's scene: both accelerators and 1 vs 2 threads (separate lines on the chart).
sweep whitted "$here/scenes/whitted.gltf" --resolution 160x120 --reference-spp 1024 --max-spp 256 \
  --accels embree,bvh --threads 1,2
sweep csg "$here/scenes/csg.gltf" --resolution 160x120 --reference-spp 1024 --max-spp 256
# The Cornell box against an independent reference: every method's error is against the true
# image, so Whitted's bias (no indirect light) shows as a floor no sample count removes.
# With Open Image Denoise installed (tools/setup-denoise.sh), the Cornell box also gets the
# "path sobol + OIDN" line (docs/denoising.md).
denoise=$("$here/tools/tray-denoise" --check 2>/dev/null && echo --denoise || true)
sweep cornell-box "$shared/reference/cornell-box.gltf" --resolution 256x256 --max-spp 256 \
  --reference "$shared/reference/cornell-box.ref.exr" $denoise
echo "make_bench_charts: wrote $out"
