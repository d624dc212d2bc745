#!/usr/bin/env python3
"""TRay's adaptive sampling against Blender Cycles 5.2's (issue 37), both measured in this run,
one thread each, on bench/cycles_compare.py's asset scenes (the asset on a ground plane, a sun
and a sky map; both renderers read the one .glb Blender exports; its conventions and its
clamp of indirect samples).

Each renderer renders its own converged reference (--ref-spp, every thread, another seed);
then, on one thread, TRay with `--noise-threshold T` for T in --tray-thresholds and Cycles with
its adaptive sampling (`use_adaptive_sampling`, `adaptive_threshold` in --cycles-thresholds,
automatic min samples, its defaults otherwise: light tree on, blue-noise pattern), both at most
--max-spp. Time: wall seconds less the renderer's 1-spp render (set-up excluded). Error: RMSE
and relMSE against the renderer's own reference (their materials differ slightly). For each
Cycles point, the time TRay needs for that error is read off TRay's error-against-time line
(log-log, between the two TRay runs around it): Cycles' time / TRay's, above 1 TRay is faster.

Usage, in a Python 3.13 venv with bpy 5.2 (../shared/notes/cycles5.md):
  build/cycles5-venv/bin/python bench/cycles_adaptive.py [--build build] [--out DIR]
      [--size 128] [--assets DamagedHelmet,WaterBottle]
"""
import argparse
import math
import os
import subprocess
import sys

import numpy as np

import cycles_compare as cc
from compare_report import loglog_crossing, relmse
import bpy  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default=os.path.join(HERE, "..", "build"))
    p.add_argument("--out", default="/tmp/tray-cycles-adaptive")
    p.add_argument("--size", type=int, default=128)
    p.add_argument("--ref-spp", type=int, default=2048)
    p.add_argument("--max-spp", type=int, default=1024)
    p.add_argument("--max-depth", type=int, default=8)
    p.add_argument("--clamp-indirect", type=float, default=10.0)
    p.add_argument("--sun", type=float, default=3.0)
    p.add_argument("--env-intensity", type=float, default=1.0)
    p.add_argument("--sky-max", type=float, default=2.0)
    p.add_argument("--assets", default="DamagedHelmet,WaterBottle")
    p.add_argument("--tray-thresholds", default="0.5,0.2,0.1,0.05,0.03,0.02,0.01,0.005")
    p.add_argument("--cycles-thresholds", default="0.1,0.05,0.02,0.01")
    p.add_argument("--tray-args", default="")
    return p.parse_args()


def runs(args, name, merged, env, renderer):
    """The renderer's reference and its adaptive runs: [(label, seconds, RMSE, relMSE)]."""
    out = os.path.join(args.out, name)

    def render(path, spp, threads=1, seed=0, threshold=None):
        if renderer == "tray":
            extra = ["--noise-threshold", threshold] if threshold else []
            return cc.render_tray(args, merged, env, spp, path, threads, seed, extra)
        cc.setup_cycles(merged, env, args.env_intensity, args.size, spp, args.max_depth, seed,
                        args.clamp_indirect)
        c = bpy.context.scene.cycles
        if threshold:
            c.use_adaptive_sampling = True
            c.adaptive_threshold = float(threshold)
            c.adaptive_min_samples = 0  # automatic
        bpy.context.scene.render.threads = threads
        return cc.render_cycles(path)

    ref_path = os.path.join(out, f"{renderer}-ref.exr")
    render(ref_path, args.ref_spp, threads=os.cpu_count(), seed=1000)
    ref = cc.read_rgb(ref_path)
    setup = render(os.path.join(out, f"{renderer}-1.exr"), 1)
    result = []
    thresholds = args.tray_thresholds if renderer == "tray" else args.cycles_thresholds
    for t in thresholds.split(","):
        path = os.path.join(out, f"{renderer}-adaptive-{t}.exr")
        seconds = max(render(path, args.max_spp, threshold=t) - setup, 1e-3)
        img = cc.read_rgb(path)
        e = math.sqrt(float(np.mean((img - ref) ** 2)))
        result.append((t, seconds, e, relmse(img, ref)))
        cc.say(f"  {name:14s} {renderer:6s} threshold {t:5s} {seconds:8.3f} s  RMSE {e:.5f}  "
               f"relMSE {result[-1][3]:.3e}")
    return result


def compare(args, name, env):
    out = os.path.join(args.out, name)
    os.makedirs(out, exist_ok=True)
    merged = os.path.join(out, "merged.glb")
    cc.build_scene(cc.ASSETS[name], merged, args.sun)
    tray = runs(args, name, merged, env, "tray")
    cycles = runs(args, name, merged, env, "cycles")
    for k, metric in ((2, "RMSE"), (3, "relMSE")):
        line = [(r[1], r[k]) for r in tray]  # TRay's (seconds, error)
        cells = []
        for c in cycles:
            tray_time = loglog_crossing(line, c[k], axis=1)
            cells.append(f"{c[0]}: {c[1] / tray_time:.2f}x" if tray_time else f"{c[0]}: outside")
        cc.say(f"  {name}: Cycles' adaptive time / TRay's adaptive time to the same {metric}: "
               + ", ".join(cells))


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    maps = os.path.join(args.out, "maps")
    subprocess.run([os.path.join(args.build, "env_bench"), "--write-maps", maps], check=True,
                   stdout=subprocess.DEVNULL, env=cc.TRAY_ENV)
    env = os.path.join(maps, "sky-soft.exr")
    subprocess.run(["oiiotool", os.path.join(maps, "sky.exr"), "--clamp:max=" + str(args.sky_max),
                    "-o", env], check=True, env=cc.TRAY_ENV)
    cc.say(f"TRay adaptive vs Cycles {bpy.app.version_string} adaptive, {args.size}x{args.size}, "
           f"one thread each, at most {args.max_spp} spp, references {args.ref_spp} spp")
    for name in args.assets.split(","):
        compare(args, name, env)
    with open(os.path.join(args.out, "report.txt"), "w") as f:
        f.write("\n".join(cc.LINES) + "\n")


if __name__ == "__main__":
    main()
