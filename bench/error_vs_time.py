#!/usr/bin/env python3
"""TRay, Mitsuba 3 and Blender Cycles 5.2 on the same axes: error against CPU seconds, every
point measured in this run (issue 37's charts), on the Cornell box, the helmets and the
sun-lit helmets. TRay and Cycles on one thread, Mitsuba's Dr.Jit on every core (one thread
deadlocks it), all by process CPU seconds.

- Scenes: `cornell` (../shared/reference/cornell-box.gltf; Mitsuba renders its own
  `mi.cornell_box()`, from which the shared reference was made), `helmets`
  (scenes/bench/heavy-helmets.gltf: textured DamagedHelmet and WaterBottle, a glossy metal
  floor, a glass sphere, a rectangular light and a constant sky) and `sun-helmets`
  (scenes/bench/sun-helmets.gltf: the same under a sun). Mitsuba reads the glTF files through
  bench/gltf_to_mitsuba.py, Cycles through Blender's importer with bench/cycles_compare.py's
  conventions (COMPAT lighting, suns of angle 0, rough dielectrics as Diffuse BSDFs, emission
  from the front only, max_bounces = depth - 2, box filter of width 1, no denoising, no glossy
  blur) and the sky of TRAY_environment as a constant world colour.
- TRay: `tray-render --integrator path` uniform (--spp), uniform with area light sampling
  (`--triangle-sampling area`; the default samples emitters by solid angle), adaptive with its
  default relative error and with `--noise-metric absolute`; the render's CPU seconds
  (tray:renderCpuSeconds: scene loading and start-up left out).
- Mitsuba 3 `llvm_ad_rgb` (bench/mitsuba_curve.py in the Mitsuba venv): `independent` and
  `ldsampler` (its best sampler on these scenes); CPU seconds after a warm-up (JIT excluded).
- Cycles 5.2 (bpy): uniform and with its own adaptive sampling (adaptive_threshold); CPU
  seconds less a 1-spp render's.
Error: RMSE, relMSE ((x - r)^2 / (r^2 + 0.01), as bench/image_error.cpp) and relMSE without the
0.1% worst pixels (one sun glint can decide a whole image's relMSE and RMSE). The Cornell box's
reference is Mitsuba's converged render for all three (they agree on it within a few 0.01%);
on the asset scenes each renderer's error is against its OWN converged render (--ref-spp,
cached in --ref-cache), since their material models differ slightly. For each TRay method the
time to the other renderers' error at the middle spp count is read off its line (log-log
between its two runs around it); above 1, TRay is faster. The uniform runs also give the CPU
time per sample: each other renderer's over TRay's at the same spp.

Usage (the bpy venv of ../shared/notes/cycles5.md; the Mitsuba venv of tools/setup-mitsuba.sh):
  build/cycles5-venv/bin/python bench/error_vs_time.py --scene cornell|helmets|sun-helmets
      [--build build] [--spp 16,64,256] [--ref-spp 1024] [--chart PNG] [--report TXT]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import cycles_compare as cc
from compare_report import LINES, loglog_crossing, relmse, render_cpu_of, rmse, say
import bpy  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
REF_DIR = os.path.join(cc.SHARED, "reference")
SCENES = {"cornell": (os.path.join(REF_DIR, "cornell-box.gltf"), 256),
          "helmets": (os.path.join(ROOT, "scenes", "bench", "heavy-helmets.gltf"), 128),
          "sun-helmets": (os.path.join(ROOT, "scenes", "bench", "sun-helmets.gltf"), 128)}
METRICS = (("rmse", "RMSE"), ("relmse_trimmed", "relMSE, 0.1% worst pixels left out"))
STYLES = {"TRay uniform": "o-", "TRay uniform, area lights": "o--",
          "TRay adaptive, relative": "s-", "TRay adaptive, absolute": "D-",
          "Mitsuba independent": "v--", "Mitsuba ldsampler": "^--", "Cycles uniform": "<:",
          "Cycles adaptive": ">:"}


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--scene", choices=sorted(SCENES), default="cornell")
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--mitsuba-python",
                   default=os.path.join(ROOT, "build", "mitsuba-venv", "bin", "python"))
    p.add_argument("--size", type=int, help="image size (default: 256 Cornell box, else 128)")
    p.add_argument("--max-depth", type=int, default=8)
    p.add_argument("--spp", default="16,64,256", help="uniform spp counts, every renderer")
    p.add_argument("--ref-spp", type=int, default=1024, help="the asset scenes' references")
    p.add_argument("--ref-cache", default=os.path.join(ROOT, "build", "error-vs-time-refs"))
    p.add_argument("--tray-relative", default="0.1,0.05,0.03,0.02")
    p.add_argument("--tray-absolute", default="0.014,0.01,0.007,0.005,0.0035")
    p.add_argument("--noise-decision", help="TRay's --noise-decision for its adaptive runs "
                   "(default: tray-render's own)")
    p.add_argument("--cycles-thresholds", default="0.1,0.05,0.02")
    p.add_argument("--repeats", type=int, default=2,
                   help="timed runs per point, TRay and Cycles: the least CPU time is kept (the "
                        "same seed gives the same image)")
    p.add_argument("--renderers", default="tray,mitsuba,cycles",
                   help="which renderers to run (comma-separated)")
    p.add_argument("--chart", help="PNG (default docs/bench/<scene>-three-renderers.png)")
    p.add_argument("--report", help="also write the report here")
    a = p.parse_args()
    a.gltf, size = SCENES[a.scene]
    a.size = a.size or size
    a.chart = a.chart or os.path.join(ROOT, "docs", "bench", f"{a.scene}-three-renderers.png")
    return a


def errors(img, ref):
    """RMSE, relMSE and relMSE without the 0.1% worst pixels (bench/image_error.cpp's)."""
    return {"rmse": rmse(img, ref), "relmse": relmse(img, ref),
            "relmse_trimmed": relmse(img, ref, trimmed=True)}


def cache_path(a, renderer):
    return os.path.join(a.ref_cache, f"{a.scene}-{renderer}-{a.size}-{a.ref_spp}.npy")


def cached(a, renderer, make):
    """A renderer's converged render of the scene (npy in --ref-cache), made when missing."""
    os.makedirs(a.ref_cache, exist_ok=True)
    path = cache_path(a, renderer)
    if not os.path.exists(path):
        np.save(path, make())
    return np.load(path).astype(np.float64)


def tray_cmd(a, out, extra, threads=1):
    return [os.path.join(a.build, "tray-render"), a.gltf, "-q", "--allow-any-path",
            "--integrator", "path", "--max-depth", str(a.max_depth), "--threads", str(threads),
            "--resolution", f"{a.size}x{a.size}", "--float", "-o", out, *extra]


def tray_points(a, tmp):
    out = os.path.join(tmp, "tray.exr")
    runs = [("uniform", f"{s} spp", ["--spp", s]) for s in a.spp.split(",")]
    runs += [("uniform, area lights", f"{s} spp", ["--spp", s, "--triangle-sampling", "area"])
             for s in a.spp.split(",")]
    decide = ["--noise-decision", a.noise_decision] if a.noise_decision else []
    runs += [("adaptive, relative", f"T {t}", ["--spp", "1024", "--noise-threshold", t, *decide])
             for t in a.tray_relative.split(",")]
    runs += [("adaptive, absolute", f"T {t}",
              ["--spp", "1024", "--noise-threshold", t, "--noise-metric", "absolute", *decide])
             for t in a.tray_absolute.split(",")]
    points = []
    for method, setting, extra in runs:
        cpu = min(render_cpu_of(tray_cmd(a, out, extra), out, env=cc.TRAY_ENV)
                  for _ in range(a.repeats))
        points.append((f"TRay {method}", setting, cpu, cc.read_rgb(out)))
    return points


def tray_reference(a, tmp):
    out = os.path.join(tmp, "tray-ref.exr")
    subprocess.run(tray_cmd(a, out, ["--spp", str(a.ref_spp), "--seed", "1000"],
                            threads=os.cpu_count()), check=True, env=cc.TRAY_ENV)
    return cc.read_rgb(out)


def mitsuba_run(a, tmp, reference):
    """bench/mitsuba_curve.py's points [(method, setting, cpu, image)], and its reference."""
    env = dict(os.environ, DRJIT_LIBLLVM_PATH="/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1")
    env.pop("OCIO", None)
    scene = "cornell" if a.scene == "cornell" else a.gltf
    cmd = [a.mitsuba_python, os.path.join(HERE, "mitsuba_curve.py"), "--scene", scene,
           "--out", os.path.join(tmp, "mitsuba"), "--size", str(a.size), "--spp", a.spp,
           "--max-depth", str(a.max_depth), "--repeats", str(a.repeats)]
    if reference:
        cmd += ["--reference-spp", str(a.ref_spp)]
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=HERE)
    if r.returncode != 0:
        sys.exit(f"mitsuba_curve.py failed: {r.stderr.strip()}")
    points, ref = [], None
    for line in r.stdout.splitlines():
        words = line.split()
        if words[:1] == ["reference"]:
            ref = np.load(words[1]).astype(np.float64)
        elif words[:1] == ["mitsuba"]:  # Mitsuba's own warnings share standard output
            _, sampler, spp, cpu, path = words
            points.append((f"Mitsuba {sampler}", f"{spp} spp", float(cpu),
                           np.load(path).astype(np.float64)))
    return points, ref


def cycles_setup(a, spp, threads=1, seed=1):
    """The scene in Cycles: cycles_compare's import and settings; the world black (Cornell
    box) or TRAY_environment's constant background."""
    scene = cc.import_merged(a.gltf)
    with open(a.gltf) as f:
        doc = json.load(f)
    env = doc["scenes"][doc.get("scene", 0)].get("extensions", {}).get("TRAY_environment", {})
    colour = env.get("background", [0, 0, 0])
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (*colour, 1.0)
    bg.inputs["Strength"].default_value = 1.0 if any(colour) else 0.0
    scene.world = world
    cc.cycles_settings(scene, a.size, spp, a.max_depth, seed=seed)
    scene.render.threads = threads


def cycles_cpu(path, repeats=1):
    """The least CPU time of `repeats` renders of the scene as set up (the same image each)."""
    bpy.context.scene.render.filepath = path
    best = float("inf")
    for _ in range(repeats):
        start = time.process_time()
        bpy.ops.render.render(write_still=True)
        best = min(best, time.process_time() - start)
    return best


def cycles_points(a, tmp):
    out = os.path.join(tmp, "cycles.exr")
    cycles_setup(a, 1)
    setup = cycles_cpu(out, a.repeats)
    points = []
    for s in a.spp.split(","):
        cycles_setup(a, int(s))
        points.append(("Cycles uniform", f"{s} spp",
                       max(cycles_cpu(out, a.repeats) - setup, 1e-3),
                       cc.read_rgb(out)))
    for t in a.cycles_thresholds.split(","):
        cycles_setup(a, 1024)
        c = bpy.context.scene.cycles
        c.use_adaptive_sampling, c.adaptive_threshold, c.adaptive_min_samples = True, float(t), 0
        points.append(("Cycles adaptive", f"T {t}", max(cycles_cpu(out, a.repeats) - setup, 1e-3),
                       cc.read_rgb(out)))
    return points


def cycles_reference(a, tmp):
    out = os.path.join(tmp, "cycles-ref.exr")
    cycles_setup(a, a.ref_spp, threads=os.cpu_count(), seed=1000)
    cycles_cpu(out)
    return cc.read_rgb(out)


def chart(a, rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    for ax, (key, label) in zip(axes, METRICS):
        for method, style in STYLES.items():
            pts = sorted((r["cpu"], r[key]) for r in rows if r["method"] == method)
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], style, label=method)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("CPU seconds (TRay, Cycles: 1 thread; Mitsuba: Dr.Jit's threads)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    against = ("Mitsuba's converged render" if a.scene == "cornell"
               else "each renderer's own converged render")
    fig.suptitle(f"{a.scene}, {a.size}x{a.size}, max depth {a.max_depth}; error against {against}")
    fig.tight_layout()
    fig.savefig(a.chart, dpi=100)


def crossings(a, rows, key):
    """For each TRay method: the other renderers' time over TRay's to their error (every
    Mitsuba ldsampler and Cycles adaptive point; the others at the middle spp count)."""
    mid = a.spp.split(",")[len(a.spp.split(",")) // 2] + " spp"
    targets = [r for r in rows if r["method"] in ("Mitsuba ldsampler", "Cycles adaptive") or (
        r["setting"] == mid and r["method"] in ("Mitsuba independent", "Cycles uniform"))]
    for tray in [m for m in STYLES if m.startswith("TRay")]:
        line = sorted((r[key], r["cpu"]) for r in rows if r["method"] == tray)
        cells = []
        for r in targets:
            t = loglog_crossing(line, r[key])
            name = f"{r['method']} {r['setting']}"
            cells.append(f"{name} {r['cpu'] / t:.2f}x" if t else f"{name} outside")
        say(f"  {key}: time to equal error, other / {tray}: " + ", ".join(cells))


def per_sample(rows):
    """Each other renderer's uniform CPU time over TRay uniform's at the same spp (above 1: TRay
    takes less per sample)."""
    tray = {r["setting"]: r["cpu"] for r in rows if r["method"] == "TRay uniform"}
    for method in ("Mitsuba independent", "Mitsuba ldsampler", "Cycles uniform"):
        cells = [f"{r['setting']} {r['cpu'] / tray[r['setting']]:.2f}x" for r in rows
                 if r["method"] == method and r["setting"] in tray]
        if cells:
            say(f"  per sample, {method} / TRay uniform: " + ", ".join(cells))


def main():
    a = parse_args()
    say(f"TRay, Mitsuba 3 and Cycles {bpy.app.version_string} on {a.scene} "
        f"({os.path.relpath(a.gltf, ROOT)}), {a.size}x{a.size}, CPU seconds (TRay and Cycles "
        f"1 thread; TRay's adaptive runs: --noise-decision {a.noise_decision or 'default'}), "
        f"measured {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} "
        f"(load {os.getloadavg()[0]:.2f})")
    with tempfile.TemporaryDirectory() as tmp:
        shared = a.scene == "cornell"
        run = a.renderers.split(",")
        mitsuba, mitsuba_ref = mitsuba_run(
            a, tmp, reference=not shared and not os.path.exists(cache_path(a, "mitsuba"))) \
            if "mitsuba" in run else ([], None)
        if shared:
            refs = dict.fromkeys(("TRay", "Mitsuba", "Cycles"),
                                 cc.read_rgb(os.path.join(REF_DIR, "cornell-box.ref.exr")))
        else:
            makers = {"TRay": ("tray", lambda: tray_reference(a, tmp)),
                      "Mitsuba": ("mitsuba", lambda: mitsuba_ref),
                      "Cycles": ("cycles", lambda: cycles_reference(a, tmp))}
            refs = {k: cached(a, *v) for k, v in makers.items() if v[0] in run}
        points = (cycles_points(a, tmp) if "cycles" in run else []) + \
            (tray_points(a, tmp) if "tray" in run else []) + mitsuba
        rows = []
        for method, setting, cpu, img in points:
            ref = refs[method.split()[0]]
            rows.append({"method": method, "setting": setting, "cpu": cpu,
                         "mean": img.mean() / ref.mean() - 1, **errors(img, ref)})
    for r in rows:
        say(f"  {r['method']:28s} {r['setting']:10s} {r['cpu']:8.3f} CPU-s  RMSE {r['rmse']:.5f}"
            f"  relMSE {r['relmse']:.5f}  trimmed {r['relmse_trimmed']:.5f}"
            f"  mean {r['mean'] * 100:+.3f}%")
    for key, _ in METRICS:
        crossings(a, rows, key)
    per_sample(rows)
    chart(a, rows)
    say(f"  chart: {os.path.relpath(a.chart, ROOT)}")
    if a.report:
        with open(a.report, "w") as f:
            f.write("\n".join(LINES) + "\n")


if __name__ == "__main__":
    main()
