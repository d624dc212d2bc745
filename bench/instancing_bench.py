#!/usr/bin/env python3
"""EXT_mesh_gpu_instancing benchmark (docs/instancing.md, docs/bench/instancing-*.md).

Writes one sphere instanced 1, 10^3 and 10^6 times (tools/make_instancing_scene.py --count N,
into --dir, not the repo), then for each scene and accelerator:
  - tray-render under /usr/bin/time -v: peak RSS ("Maximum resident set size") and wall time;
  - build/instancing_bench: resident set and seconds per phase (load, build, render).
Compares peak memory against the issue's budget (one instance's geometry + 64 bytes per
instance, within 2x) and render time of 10^6 against 10^3 instances at equal spp and resolution
(within 1.5x). Prints a Markdown report. Run from the repo root after building tray-render and
instancing_bench:

  /usr/bin/python3 bench/instancing_bench.py --threads 2
"""
import argparse
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COUNTS = [1, 1000, 1000000]


def run(cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True)


def peak_rss(a, scene, accel):
    r = run(["/usr/bin/time", "-v", a.render, scene, "--allow-any-path", "--accel", accel,
             "--resolution", a.resolution, "--spp", str(a.spp), "--integrator", a.integrator,
             "--threads", str(a.threads), "-q", "-o", os.path.join(a.dir, "out.exr")] +
            (["--instance-arrays", str(a.instance_arrays)] if a.instance_arrays >= 0 else []))
    kb = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", r.stderr).group(1))
    return kb / 1024.0


def phases(a, scene, accel):
    r = run([a.bench, scene, accel, a.resolution, str(a.spp), a.integrator] +
            ([str(a.instance_arrays)] if a.instance_arrays >= 0 else []))
    out = {}
    for line in r.stdout.splitlines():
        m = re.match(r"(\w+)\s+wall\s+([\d.]+) s\s+cpu\s+([\d.]+) s\s+rss\s+([\d.]+) MiB", line)
        if m:
            out[m.group(1)] = (float(m.group(2)), float(m.group(3)), float(m.group(4)))
        m = re.match(r"\d+ primitives over \d+ meshes \((\d+) triangles, (\d+) vertices\)", line)
        if m:
            out["tris"], out["verts"] = int(m.group(1)), int(m.group(2))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--dir", default="/tmp/tray-instancing-bench")
    ap.add_argument("--render", default=os.path.join(ROOT, "build", "tray-render"))
    ap.add_argument("--bench", default=os.path.join(ROOT, "build", "instancing_bench"))
    ap.add_argument("--resolution", default="256x256")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--integrator", default="path")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--segments", type=int, default=32)
    ap.add_argument("--instance-arrays", type=int, default=-1,
                    help="tray-render --instance-arrays: sets of this many instances or more load "
                         "as instance arrays; 0: one primitive per instance; -1 (default): not "
                         "passed (the binaries' default; builds before the option)")
    a = ap.parse_args()
    os.makedirs(a.dir, exist_ok=True)
    scenes = {}
    for n in COUNTS:
        scenes[n] = os.path.join(a.dir, "grid%d.gltf" % n)
        if not os.path.exists(scenes[n]):
            run([sys.executable, os.path.join(ROOT, "tools", "make_instancing_scene.py"),
                 "--count", str(n), "--segments", str(a.segments), "--out", scenes[n]])
    print("| accel | instances | peak RSS (MiB) | over 1 instance (MiB) | bytes/instance | "
          "budget 2x(geom + 64 B/inst) (MiB) | load s | build s | render s (cpu) |")
    print("|---|---|---|---|---|---|---|---|---|")
    renders = {}
    for accel in ("embree", "bvh"):
        base = None
        for n in COUNTS:
            peak = peak_rss(a, scenes[n], accel)
            p = phases(a, scenes[n], accel)
            geom = p["verts"] * 24 + p["tris"] * 12  # positions + normals, uint32 indices
            budget = 2 * (geom + 64 * n) / 2**20
            base = peak if base is None else base
            per = (peak - base) * 2**20 / n if n > 1 else float("nan")
            renders[(accel, n)] = p["render"]
            print("| %s | %d | %.1f | %.1f | %.0f | %.2f | %.2f | %.2f | %.3f (%.3f) |" % (
                accel, n, peak, peak - base, per, budget, p["load"][0], p["build"][0],
                p["render"][0], p["render"][1]))
    print()
    for accel in ("embree", "bvh"):
        w6, c6 = renders[(accel, 1000000)][:2]
        w3, c3 = renders[(accel, 1000)][:2]
        print("%s: render time 10^6 / 10^3 instances: wall %.2fx, cpu %.2fx" % (
            accel, w6 / w3, c6 / c3))


if __name__ == "__main__":
    main()
