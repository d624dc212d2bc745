#!/usr/bin/env python3
"""Where each light-transport method fails, charted (issue 38): error against CPU time for
`path`, `bdpt` and `sppm` on the scenes that separate them (scenes/transport/, the helmets).

For every scene and method it renders a ladder of sample counts on one thread, measures the
CPU seconds of each tray-render run, and the RMSE and relMSE against the scene's reference: the
longest render of the method named in SCENES (its converged image), checked against the other
methods' longest renders (their means, and the mean over the region where the reference is
brightest). Writes <out>/transport.csv, transport.txt (the report) and transport.png (one
column per scene, RMSE above relMSE, log-log).

  /usr/bin/python3 bench/transport_compare.py --build build --out /tmp/transport \
      [--scenes caustic-spot,glossy-pair] [--methods path,bdpt,sppm] [--quick]
"""
import argparse
import csv
import math
import os
import resource
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
sys.path.insert(0, HERE)
from compare_report import loglog_crossing  # noqa: E402

# Each method: its tray-render options and a ladder of --spp (sppm: iterations).
METHODS = {
    "path": (["--integrator", "path"], [4, 16, 64, 256]),
    "bdpt": (["--integrator", "bdpt"], [2, 8, 32, 128]),
    "sppm": (["--integrator", "sppm", "--photons", "20000"], [4, 16, 64, 256]),
}
# Each scene: file, options, the method whose longest render is the reference, and how much
# longer than the ladder's top that reference runs.
SCENES = {
    "caustic-spot": ("scenes/transport/caustic-spot.gltf",
                     ["--max-depth", "5", "--resolution", "200x200"], "bdpt", 2),
    "caustic-glass": ("scenes/transport/caustic-glass.gltf",
                      ["--max-depth", "8", "--resolution", "160x106"], "sppm", 4),
    "small-opening": ("scenes/transport/small-opening.gltf",
                      ["--max-depth", "8", "--resolution", "160x106"], "bdpt", 4),
    "glossy-pair": ("scenes/transport/glossy-pair.gltf",
                    ["--max-depth", "8", "--resolution", "160x106"], "bdpt", 4),
    "helmets": ("scenes/bench/heavy-helmets.gltf",
                ["--max-depth", "8", "--resolution", "160x106", "--allow-any-path"], "path", 4),
}


def read(path):
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(path)
    if not inp:
        sys.exit(f"transport_compare: {path}: cannot open")
    px = inp.read_image(0, 0, 0, 3, "float").astype(np.float64)
    inp.close()
    return px


def render(args, scene, method, spp, out, seed=0):
    """One single-threaded tray-render run; its CPU seconds (user + system of the child)."""
    file, scene_opts, _, _ = SCENES[scene]
    opts, _ = METHODS[method]
    cmd = [os.path.join(args.build, "tray-render"), os.path.join(ROOT, file), "-q", "--float",
           "--threads", "1", "--spp", str(spp), "--seed", str(seed), "-o", out] + opts + scene_opts
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    run = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if run.returncode != 0:
        sys.exit(f"transport_compare: {' '.join(cmd)}: {run.stderr.strip()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall


def errors(img, ref):
    d = img - ref
    rmse = float(np.sqrt(np.mean(d * d)))
    lum = ref.mean(axis=2, keepdims=True)
    relmse = float(np.mean(d * d / (lum * lum + 0.01)))
    return rmse, relmse


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"),
                    help="folder of tray-render (with its ocio/ beside it)")
    ap.add_argument("--out", default="/tmp/transport")
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--methods", default=",".join(METHODS))
    ap.add_argument("--quick", action="store_true", help="the ladders' first two rungs only")
    ap.add_argument("--from-csv", action="store_true",
                    help="no renders: the summary and chart of the run in --out")
    args = ap.parse_args()
    if args.from_csv:
        return from_csv(args)
    os.makedirs(args.out, exist_ok=True)
    report, rows = [], []

    def say(text=""):
        print(text, flush=True)
        report.append(text)

    scenes, methods = args.scenes.split(","), args.methods.split(",")
    for scene in scenes:
        _, _, ref_method, factor = SCENES[scene]
        folder = os.path.join(args.out, scene)
        os.makedirs(folder, exist_ok=True)
        # Each method's converged image: its ladder's top times `factor`, another seed.
        longest = {}
        for m in methods:
            spp = METHODS[m][1][-1 if not args.quick else 1] * factor
            path = os.path.join(folder, f"{m}-reference.exr")
            if not os.path.exists(path):
                cpu, _ = render(args, scene, m, spp, path, seed=7)
                say(f"{scene}: {m} reference, {spp} spp, {cpu:.1f} CPU s")
            longest[m] = read(path)
        ref = longest[ref_method if ref_method in longest else methods[0]]
        bright = ref.mean(axis=2) >= np.quantile(ref.mean(axis=2), 0.9)
        say(f"{scene}: reference {ref_method}; means (R, G, B) and the brightest 10%:")
        for m, img in longest.items():
            mean, mb = img.mean(axis=(0, 1)), img[bright].mean()
            rel = mean.mean() / max(ref.mean(), 1e-30) - 1
            relb = mb / max(ref[bright].mean(), 1e-30) - 1
            say(f"  {m:5s} {mean[0]:.5f} {mean[1]:.5f} {mean[2]:.5f}  "
                f"({100 * rel:+.2f}%; brightest 10% {100 * relb:+.2f}%)")
        for m in methods:
            ladder = METHODS[m][1][:2] if args.quick else METHODS[m][1]
            for spp in ladder:
                path = os.path.join(folder, f"{m}-{spp}.exr")
                cpu, wall = render(args, scene, m, spp, path)
                rmse, relmse = errors(read(path), ref)
                rows.append(dict(scene=scene, method=m, spp=spp, cpu_seconds=round(cpu, 3),
                                 rmse=rmse, relmse=relmse))
                say(f"  {m:5s} {spp:5d} spp  {cpu:8.2f} CPU s  RMSE {rmse:.5f}  "
                    f"relMSE {relmse:.5f}")
        for line in summary(rows, scene, methods):
            say(line)
    with open(os.path.join(args.out, "transport.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(args.out, "transport.txt"), "w") as f:
        f.write("\n".join(report) + "\n")
    chart(rows, scenes, methods, os.path.join(args.out, "transport.png"))


def summary(rows, scene, methods):
    """Lines saying how soon each method reaches path's error at its largest budget (RMSE and
    relMSE), read off the log-log lines through each method's rungs."""
    out = []
    best = [r for r in rows if r["scene"] == scene and r["method"] == "path"]
    if not best:
        return out
    for metric in ("rmse", "relmse"):
        target, path_time = best[-1][metric], best[-1]["cpu_seconds"]
        for m in methods:
            pts = sorted((r["cpu_seconds"], r[metric]) for r in rows
                         if r["scene"] == scene and r["method"] == m)
            if not pts:
                continue
            t = loglog_crossing(pts, target, axis=1)
            if t is None and pts[0][1] <= target:
                text = f"below it from the first rung ({pts[0][0]:.2f} s, {path_time / pts[0][0]:.1f}x sooner or more)"
            elif t is None:
                text = f"not reached (best {min(p[1] for p in pts):.5f} at {pts[-1][0]:.2f} s)"
            else:
                text = f"{t:.2f} s ({path_time / t:.2f}x path's {path_time:.2f} s)"
            out.append(f"  {m:5s} to path's top-rung {metric} {target:.5f}: {text}")
    return out


def from_csv(args):
    """The summary and chart of an earlier run, from its CSV."""
    with open(os.path.join(args.out, "transport.csv")) as f:
        rows = [dict(r, spp=int(r["spp"]), cpu_seconds=float(r["cpu_seconds"]),
                     rmse=float(r["rmse"]), relmse=float(r["relmse"])) for r in csv.DictReader(f)]
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    methods = list(dict.fromkeys(r["method"] for r in rows))
    for scene in scenes:
        print(scene)
        for line in summary(rows, scene, methods):
            print(line)
    chart(rows, scenes, methods, os.path.join(args.out, "transport.png"))


def chart(rows, scenes, methods, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, len(scenes), figsize=(3.2 * len(scenes), 6), squeeze=False)
    for c, scene in enumerate(scenes):
        for r, metric in enumerate(("rmse", "relmse")):
            ax = axes[r][c]
            for m in methods:
                pts = [(x["cpu_seconds"], x[metric]) for x in rows
                       if x["scene"] == scene and x["method"] == m]
                if pts:
                    ax.loglog(*zip(*pts), marker="o", label=m)
            ax.set_title(f"{scene}" if r == 0 else "")
            ax.set_xlabel("CPU seconds (1 thread)")
            ax.set_ylabel("RMSE" if r == 0 else "relMSE")
            ax.grid(True, which="both", alpha=0.3)
    axes[0][0].legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
