#!/usr/bin/env python3
"""TRay, Mitsuba 3 and Blender Cycles 5.2 on the same axes: RMSE against CPU seconds on the
Cornell box, measured in this run (issue 37's charts): TRay and Cycles on one thread, Mitsuba's
Dr.Jit on every core (one thread deadlocks it), all by process CPU seconds.

- TRay: `tray-render --integrator path` uniform (--spp), adaptive with its default relative
  error (--noise-threshold) and with --noise-metric absolute; CPU seconds of the whole run
  less a 1-spp run's (scene load and BVH excluded).
- Mitsuba 3 `llvm_ad_rgb` (bench/mitsuba_cornell_curve.py in the Mitsuba venv): `independent`
  and `ldsampler`, its best sampler on this scene; CPU seconds of the render after a warm-up
  (JIT compilation excluded).
- Cycles 5.2 (bpy): the shared glTF through Blender's importer with bench/cycles_compare.py's
  conventions (COMPAT lighting, a Diffuse BSDF for TRay's Lambertian materials, max_bounces =
  depth - 2, box filter of width 1, no denoising, no glossy blur), uniform and with its own
  adaptive sampling (adaptive_threshold); CPU seconds of the render less a 1-spp render's.
Error: RMSE over all pixels and channels against ../shared/reference/cornell-box.ref.exr
(Mitsuba, 4096 spp), and each render's mean relative to the reference's (the three renderers
agree on this scene within a few 0.01%). For each TRay method, the time to Mitsuba's and
Cycles' best error at 64 spp is read off its line (log-log between its two runs around it).

Usage (the bpy venv of ../shared/notes/cycles5.md; the Mitsuba venv of tools/setup-mitsuba.sh):
  build/cycles5-venv/bin/python bench/cornell_error_vs_time.py [--build build]
      [--spp 16,64,256] [--chart PNG] [--report TXT]   (at the reference's 256x256)
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time


import cycles_compare as cc
from compare_report import LINES, cpu_of, loglog_crossing, rmse, say
import bpy  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REF_DIR = os.path.join(cc.SHARED, "reference")


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default=os.path.join(HERE, "..", "build"))
    p.add_argument("--mitsuba-python", default=os.path.join(HERE, "..", "build", "mitsuba-venv",
                                                            "bin", "python"))
    p.add_argument("--max-depth", type=int, default=8)
    p.add_argument("--spp", default="16,64,256", help="uniform spp counts, every renderer")
    p.add_argument("--tray-relative", default="0.1,0.05,0.03,0.02")
    p.add_argument("--tray-absolute", default="0.014,0.01,0.007,0.005,0.0035")
    p.add_argument("--cycles-thresholds", default="0.1,0.05,0.02")
    p.add_argument("--chart", default=os.path.join(HERE, "..", "docs", "bench",
                                                   "cornell-three-renderers.png"))
    p.add_argument("--report", help="also write the report here")
    return p.parse_args()


def tray_cpu(args, extra, out):
    """CPU seconds (user + system) of one single-threaded tray-render of the Cornell box."""
    cmd = [os.path.join(args.build, "tray-render"), os.path.join(REF_DIR, "cornell-box.gltf"),
           "-q", "--allow-any-path", "--integrator", "path", "--max-depth", str(args.max_depth),
           "--threads", "1", "--resolution", f"{args.size}x{args.size}", "--float", "-o", out,
           *extra]
    return cpu_of(cmd, env=cc.TRAY_ENV)


def tray_points(args, tmp):
    out = os.path.join(tmp, "tray.exr")
    setup = tray_cpu(args, ["--spp", "1"], out)
    runs = [("uniform", f"{s} spp", ["--spp", s]) for s in args.spp.split(",")]
    runs += [("adaptive, relative", f"T {t}", ["--spp", "1024", "--noise-threshold", t])
             for t in args.tray_relative.split(",")]
    runs += [("adaptive, absolute", f"T {t}",
              ["--spp", "1024", "--noise-threshold", t, "--noise-metric", "absolute"])
             for t in args.tray_absolute.split(",")]
    points = []
    for method, setting, extra in runs:
        cpu = max(tray_cpu(args, extra, out) - setup, 1e-3)
        points.append((f"TRay {method}", setting, cpu, cc.read_rgb(out)))
    return points


def mitsuba_points(args):
    env = dict(os.environ, DRJIT_LIBLLVM_PATH="/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1")
    r = subprocess.run([args.mitsuba_python, os.path.join(HERE, "mitsuba_cornell_curve.py"),
                        "--size", str(args.size), "--spp", args.spp, "--max-depth",
                        str(args.max_depth)],
                       capture_output=True, text=True, env=env)
    if r.returncode != 0:
        sys.exit(f"mitsuba_cornell_curve.py failed: {r.stderr.strip()}")
    points = []
    for line in r.stdout.splitlines():
        if not line.startswith("mitsuba "):  # Mitsuba's own warnings share standard output
            continue
        _, sampler, spp, cpu, err = line.split()
        points.append((f"Mitsuba {sampler}", f"{spp} spp", float(cpu), float(err)))
    return points


def cycles_setup(args, spp):
    """The Cornell box in Cycles: bench/cycles_compare.py's import and settings, a black world,
    seed 1."""
    scene = cc.import_merged(os.path.join(REF_DIR, "cornell-box.gltf"))
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    cc.cycles_settings(scene, args.size, spp, args.max_depth, seed=1)


def cycles_cpu(path):
    bpy.context.scene.render.filepath = path
    start = time.process_time()
    bpy.ops.render.render(write_still=True)
    return time.process_time() - start


def cycles_points(args, tmp):
    out = os.path.join(tmp, "cycles.exr")
    cycles_setup(args, 1)
    setup = cycles_cpu(out)
    points = []
    for s in args.spp.split(","):
        cycles_setup(args, int(s))
        points.append(("Cycles uniform", f"{s} spp", max(cycles_cpu(out) - setup, 1e-3),
                       cc.read_rgb(out)))
    for t in args.cycles_thresholds.split(","):
        cycles_setup(args, 1024)
        c = bpy.context.scene.cycles
        c.use_adaptive_sampling, c.adaptive_threshold, c.adaptive_min_samples = True, float(t), 0
        points.append(("Cycles adaptive", f"T {t}", max(cycles_cpu(out) - setup, 1e-3),
                       cc.read_rgb(out)))
    return points


def chart(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.5, 5))
    styles = {"TRay uniform": "o-", "TRay adaptive, relative": "s-",
              "TRay adaptive, absolute": "D-", "Mitsuba independent": "v--",
              "Mitsuba ldsampler": "^--", "Cycles uniform": "<:", "Cycles adaptive": ">:"}
    for method, style in styles.items():
        pts = sorted((cpu, err) for m, _, cpu, err, _ in rows if m == method)
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], style, label=method)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("CPU seconds (TRay, Cycles: 1 thread; Mitsuba: Dr.Jit's threads); set-up, JIT excluded")
    ax.set_ylabel("RMSE against Mitsuba's 4096-spp reference")
    ax.set_title("Cornell box, 256x256, max depth 8")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    args = parse_args()
    ref = cc.read_rgb(os.path.join(REF_DIR, "cornell-box.ref.exr"))
    args.size = ref.shape[1]
    say(f"TRay, Mitsuba 3 and Cycles {bpy.app.version_string} on the Cornell box, "
        f"{args.size}x{args.size}, CPU seconds (TRay and Cycles 1 thread), measured "
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} (load {os.getloadavg()[0]:.2f})")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for method, setting, cpu, img in cycles_points(args, tmp) + tray_points(args, tmp):
            err = rmse(img, ref)
            rows.append((method, setting, cpu, err, img.mean() / ref.mean() - 1))
    for method, setting, cpu, err in mitsuba_points(args):
        rows.append((method, setting, cpu, err, float("nan")))
    for method, setting, cpu, err, bias in rows:
        mean = "" if bias != bias else f"  mean {bias * 100:+.3f}%"
        say(f"  {method:24s} {setting:10s} {cpu:8.3f} CPU-s  RMSE {err:.5f}{mean}")
    # Time to the other renderers' error at the middle spp count, read off each TRay line.
    mid = args.spp.split(",")[len(args.spp.split(",")) // 2] + " spp"
    targets = [(m, cpu, err) for m, s, cpu, err, _ in rows
               if s == mid and m in ("Mitsuba ldsampler", "Mitsuba independent", "Cycles uniform")]
    targets += [(f"{m} {s}", cpu, err) for m, s, cpu, err, _ in rows if m == "Cycles adaptive"]
    for tray in ("TRay uniform", "TRay adaptive, relative", "TRay adaptive, absolute"):
        line = sorted((err, cpu) for m, _, cpu, err, _ in rows if m == tray)
        cells = []
        for name, cpu, err in targets:
            t = loglog_crossing(line, err)
            cells.append(f"{name} {cpu / t:.2f}x" if t else f"{name} outside")
        say(f"  time to equal RMSE, other / {tray}: " + ", ".join(cells))
    chart(rows, args.chart)
    say(f"  chart: {args.chart}")
    if args.report:
        with open(args.report, "w") as f:
            f.write("\n".join(LINES) + "\n")


if __name__ == "__main__":
    main()
