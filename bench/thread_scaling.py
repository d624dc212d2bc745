#!/usr/bin/env python3
"""Thread scaling of the path tracers (issue 16): wall-clock Msamples/s of `path-scalar` and
`path` (the wavefront) at 1, 2, 4, ... threads, from build/path_bench, with the speed-up and the
parallel efficiency (speed-up / threads) against one thread measured in the same run.

    python3 bench/thread_scaling.py                      # Cornell box, 1..nproc threads
    python3 bench/thread_scaling.py --threads 1,2,4,8,16 --size 256 --spp 64 \\
        --scene ../shared/reference/cornell-box.gltf --scene /tmp/staged/heavy-spheres.gltf

Wall-clock time is what scaling is about, so run it on an otherwise idle machine: on shared
cores the efficiency measures the other work too (the script prints the load average before
and after each scene). Each count is run `--repeats` times and the best kept. Exits non-zero
if path_bench fails or prints something it cannot parse; it asserts nothing about the figures.
"""
import argparse
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RATE = re.compile(r"^\s+Msamples/s\s+([0-9.]+)", re.M)


def wall_rates(bench, scene, threads, size, spp, accel):
    """(path-scalar, path) wall-clock Msamples/s of one path_bench run (in that order)."""
    cmd = [bench, scene, str(threads), str(size), str(spp), "--no-replay", "--no-error",
           "--accel", accel]
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"thread_scaling: {' '.join(cmd)} failed:\n{out.stderr}")
    rates = [float(r) for r in RATE.findall(out.stdout)]
    if len(rates) != 2:
        sys.exit(f"thread_scaling: cannot read two Msamples/s lines from:\n{out.stdout}")
    return rates


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"), help="where path_bench is")
    p.add_argument("--scene", action="append", help="glTF scene (repeatable); default: the "
                   "shared Cornell box")
    p.add_argument("--threads", default=None,
                   help="comma-separated thread counts (default: powers of two up to nproc)")
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--spp", type=int, default=32)
    p.add_argument("--accel", default="embree")
    p.add_argument("--repeats", type=int, default=2)
    a = p.parse_args()
    bench = os.path.join(a.build, "path_bench")
    if not os.access(bench, os.X_OK):
        sys.exit(f"thread_scaling: {bench} not found (cmake --build build --target path_bench)")
    scenes = a.scene or [os.path.join(ROOT, "..", "shared", "reference", "cornell-box.gltf")]
    if a.threads:
        counts = [int(t) for t in a.threads.split(",")]
    else:
        counts, t = [], 1
        while t <= os.cpu_count():
            counts.append(t)
            t *= 2
    if counts[0] != 1:
        counts.insert(0, 1)
    print(f"thread scaling: {a.size}x{a.size}, {a.spp} spp, accel {a.accel}, "
          f"{os.cpu_count()} logical CPUs, best of {a.repeats}")
    for scene in scenes:
        load = os.getloadavg()[0]
        print(f"\n{os.path.basename(scene)} (load average {load:.1f} before)")
        print("threads | path-scalar Msamples/s | speed-up | efficiency | path Msamples/s | "
              "speed-up | efficiency")
        base = None
        for t in counts:
            best = [0.0, 0.0]
            for _ in range(a.repeats):
                rates = wall_rates(bench, scene, t, a.size, a.spp, a.accel)
                best = [max(b, r) for b, r in zip(best, rates)]
            base = base or best
            cells = []
            for b, r in zip(base, best):
                cells += [f"{r:.3f}", f"{r / b:.2f}x", f"{r / b / t:.0%}"]
            print(f"{t:7d} | " + " | ".join(cells))
        print(f"(load average {os.getloadavg()[0]:.1f} after)")


if __name__ == "__main__":
    main()
