#!/usr/bin/env python3
"""TRay's path tracer against Mitsuba 3, both measured in this run on this machine.

Speed: Mitsuba's Cornell box (mi.cornell_box(), path max_depth 8, box filter, independent
sampler) at --size/--spp in the llvm_ad_rgb and scalar_rgb variants (one warm-up render so JIT
compilation is excluded, then best of --repeats), and TRay's path_bench on the same scene as glTF
(best of --repeats). Error: both at the reference's 256x256 and --error-spp against Mitsuba's
converged render (/work/shared/reference/cornell-box.ref.exr); TRay with its default (Sobol'
numbers, jittered pixel positions), with independent numbers, and independent throughout like
Mitsuba's independent sampler.

Run with the venv of tools/setup-mitsuba.sh (tools/compare-mitsuba.sh does it all).
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

try:
    import drjit as dr
    import mitsuba as mi
    import numpy as np
except ImportError as e:
    print(f"mitsuba_compare: {e}: run tools/setup-mitsuba.sh and use build/mitsuba-venv/bin/python",
          file=sys.stderr)
    sys.exit(2)

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.normpath(os.path.join(HERE, "..", "..", "shared", "reference"))
LINES = []


def say(text=""):
    print(text, flush=True)
    LINES.append(text)


def fail(text):
    print(f"mitsuba_compare: {text}", file=sys.stderr)
    sys.exit(1)


# Mitsuba 3's samplers that stratify (its default, `independent`, does not).
MITSUBA_STRATIFIED = ("stratified", "ldsampler")


def mitsuba_scene(size, spp, depth, sampler="independent"):
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = size
    d["sensor"]["film"]["height"] = size
    d["sensor"]["film"]["rfilter"] = {"type": "box"}
    d["sensor"]["sampler"] = {"type": sampler, "sample_count": spp}
    d["integrator"] = {"type": "path", "max_depth": depth}
    return mi.load_dict(d)


def mitsuba_render(scene, spp, seed):
    img = mi.render(scene, spp=spp, seed=seed)
    dr.eval(img)
    dr.sync_thread()  # the llvm variant renders asynchronously: wait before stopping the clock
    return img


def mitsuba_speed(variant, size, spp, depth, repeats, sampler="independent"):
    mi.set_variant(variant)
    scene = mitsuba_scene(size, spp, depth, sampler)
    t = time.perf_counter()
    mitsuba_render(scene, spp, 0)  # warm-up: JIT compile (llvm) and first-touch allocations
    warm = time.perf_counter() - t
    best, best_cpu = float("inf"), float("inf")
    for i in range(repeats):
        t, c = time.perf_counter(), time.process_time()  # process time: all of Dr.Jit's threads
        mitsuba_render(scene, spp, i + 1)
        best = min(best, time.perf_counter() - t)
        best_cpu = min(best_cpu, time.process_time() - c)
    n = size * size * spp * 1e-6
    name = variant if sampler == "independent" else f"{variant} {sampler}"
    say(f"  Mitsuba {name:12s} best {best:7.2f} s  {n / best:7.3f} Msamples/s  "
        f"{n / best_cpu:7.3f} per CPU-s  (warm-up {warm:.2f} s)")
    return n / best, n / best_cpu


def tray_speed(bench, gltf, threads, size, spp, repeats, sampler):
    """Best of `repeats` path_bench runs: (Msamples/s, per CPU-second) of the scalar `path`, then
    of `path-wavefront` (path_bench measures both in each run, in that order)."""
    best = [0.0] * 4
    for _ in range(repeats):
        r = subprocess.run([bench, gltf, str(threads), str(size), str(spp), "--sampler", sampler,
                            "--no-replay", "--no-error"], capture_output=True, text=True)
        if r.returncode != 0:
            fail(f"{bench} failed (exit {r.returncode}): {r.stderr.strip() or r.stdout.strip()}")
        wall = re.findall(r"Msamples/s\s+([0-9.]+)", r.stdout)
        cpu = re.findall(r"([0-9.]+) Msamples per CPU-second", r.stdout)
        if len(wall) < 2 or len(cpu) < 2:
            fail(f"{bench}: expected 'Msamples/s' and 'Msamples per CPU-second' for path and "
                 f"path-wavefront in its output:\n{r.stdout}")
        now = [float(wall[0]), float(cpu[0]), float(wall[1]), float(cpu[1])]
        best = [max(b, n) for b, n in zip(best, now)]
    for label, w, c in (("", best[0], best[1]), (" wavefront", best[2], best[3])):
        say(f"  TRay{label:10s} {sampler:12s} best {size * size * spp / w * 1e-6:7.2f} s  "
            f"{w:7.3f} Msamples/s  {c:7.3f} per CPU-s  ({threads} threads)")
    return best


def read_rgb(path):
    """Linear RGB float array (H, W, 3) of an EXR: its first three channels."""
    try:
        bmp = mi.Bitmap(path)
    except Exception as e:  # mitsuba raises RuntimeError subclasses for unreadable files
        fail(f"{path}: cannot read: {e}")
    a = np.array(bmp, dtype=np.float64)
    if a.ndim != 3 or a.shape[2] < 3:
        fail(f"{path}: expected an RGB image, got array shape {a.shape}")
    return a[:, :, :3]


def tray_render(a, tmp, res, spp, extra):
    out = os.path.join(tmp, "tray.exr")
    if os.path.exists(out):
        os.remove(out)
    cmd = [a.tray_render, "--integrator", "path", "--spp", str(spp), "--max-depth",
           str(a.max_depth), "--resolution", res, "--float", *extra, a.gltf, "-o", out]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0 or not os.path.exists(out):
        fail(f"{' '.join(cmd)} failed (exit {r.returncode}): {r.stderr.strip()}")
    return read_rgb(out)


def report_error(name, img, ref):
    if img.shape != ref.shape:
        fail(f"{name}: image shape {img.shape} differs from the reference's {ref.shape}")
    if not np.all(np.isfinite(img)):
        fail(f"{name}: image has NaN or infinite pixels")
    rmse = float(np.sqrt(np.mean((img - ref) ** 2)))
    means = img.reshape(-1, 3).mean(axis=0)
    rel = (means / ref.reshape(-1, 3).mean(axis=0) - 1) * 100
    say(f"  {name:24s} RMSE {rmse:.5f}  means R {means[0]:.5f} G {means[1]:.5f} B {means[2]:.5f}"
        f"  ({rel[0]:+.2f}% {rel[1]:+.2f}% {rel[2]:+.2f}%)")
    return rmse


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--tray-bench", default=os.path.join(HERE, "..", "build", "path_bench"))
    p.add_argument("--tray-render", default=os.path.join(HERE, "..", "build", "tray-render"))
    p.add_argument("--gltf", default=os.path.join(SHARED, "cornell-box.gltf"))
    p.add_argument("--reference", default=os.path.join(SHARED, "cornell-box.ref.exr"))
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--max-depth", type=int, default=8)
    p.add_argument("--threads", type=int, default=2, help="TRay's threads (Mitsuba uses all cores)")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--error-spp", type=int, default=64)
    p.add_argument("--report", help="also write the report to this text file")
    a = p.parse_args()
    for f in (a.tray_bench, a.tray_render, a.gltf, a.reference):
        if not os.path.exists(f):
            fail(f"{f}: not found")

    say(f"TRay vs Mitsuba {mi.__version__} (drjit {dr.__version__}), Cornell box, measured "
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} on {os.cpu_count()} cores "
        f"(load {os.getloadavg()[0]:.2f})")
    say(f"Speed: {a.size}x{a.size}, {a.spp} spp, max depth {a.max_depth}, best of {a.repeats}")
    mi_llvm = mitsuba_speed("llvm_ad_rgb", a.size, a.spp, a.max_depth, a.repeats)
    mi_scalar = mitsuba_speed("scalar_rgb", a.size, a.spp, a.max_depth, a.repeats)
    # Mitsuba's own stratified samplers, for a best-against-best comparison at equal error.
    mi_better = {smp: mitsuba_speed("llvm_ad_rgb", a.size, a.spp, a.max_depth, a.repeats, smp)
                 for smp in MITSUBA_STRATIFIED}
    # Per sample, like for like: TRay's independent sequence; its default, Sobol', costs more
    # per sample and is worth more (the error section).
    tray = tray_speed(a.tray_bench, a.gltf, a.threads, a.size, a.spp, a.repeats, "independent")
    tray_sobol = tray_speed(a.tray_bench, a.gltf, a.threads, a.size, a.spp, a.repeats, "sobol")
    for name, m in (("llvm_ad_rgb", mi_llvm), ("scalar_rgb", mi_scalar)):
        say(f"  TRay independent / Mitsuba {name:12s} {tray[0] / m[0]:.2f} (wall clock), "
            f"{tray[1] / m[1]:.2f} (per CPU-second); path-wavefront {tray[2] / m[0]:.2f}, "
            f"{tray[3] / m[1]:.2f}")
    say(f"  (load at the end of the speed runs: {os.getloadavg()[0]:.2f}; per CPU-second figures"
        " depend less on other jobs)")

    ref = read_rgb(a.reference)
    size = ref.shape[1]
    m = ref.reshape(-1, 3).mean(axis=0)
    say()
    say(f"Error: {size}x{ref.shape[0]}, {a.error_spp} spp (Mitsuba: independent sampler), against "
        f"{os.path.basename(a.reference)} (means R {m[0]:.5f} G {m[1]:.5f} B {m[2]:.5f})")
    rmse = {}
    for variant in ("llvm_ad_rgb", "scalar_rgb"):
        mi.set_variant(variant)
        img = mitsuba_render(mitsuba_scene(size, a.error_spp, a.max_depth), a.error_spp, 1)
        rmse[variant] = report_error(f"Mitsuba {variant}", np.array(img, dtype=np.float64), ref)
    mi.set_variant("llvm_ad_rgb")
    for smp in MITSUBA_STRATIFIED:
        img = mitsuba_render(mitsuba_scene(size, a.error_spp, a.max_depth, smp), a.error_spp, 1)
        rmse[smp] = report_error(f"Mitsuba llvm {smp}", np.array(img, dtype=np.float64), ref)
    res = f"{size}x{ref.shape[0]}"
    with tempfile.TemporaryDirectory() as tmp:
        # TRay's default: Owen-scrambled Sobol' numbers (--sampler sobol), camera rays at the
        # sequence's own 2D points (--pixel-sampler auto = sequence at power-of-two spp).
        img = tray_render(a, tmp, res, a.error_spp, [])
        rmse["tray"] = report_error("TRay path (default)", img, ref)
        # Independent numbers, jittered pixel positions (one per stratum of an 8x8 grid).
        img = tray_render(a, tmp, res, a.error_spp, ["--sampler", "independent"])
        rmse["tray_jitter"] = report_error("TRay path (jitter)", img, ref)
        # Like-for-like with Mitsuba's independent sampler: independent numbers, and camera
        # rays at the sequence's own (then uniform) points.
        img = tray_render(a, tmp, res, a.error_spp,
                          ["--sampler", "independent", "--pixel-sampler", "sequence"])
        rmse["tray_indep"] = report_error("TRay path (independent)", img, ref)
    for name in ("llvm_ad_rgb", "scalar_rgb"):
        say(f"  RMSE TRay / Mitsuba {name:12s} {rmse['tray_indep'] / rmse[name]:.3f} (independent)"
            f", {rmse['tray_jitter'] / rmse[name]:.3f} (jitter), {rmse['tray'] / rmse[name]:.3f}"
            " (TRay's default)")
    say("  (1 = the same error at equal spp; both renderers are unbiased)")
    # Monte Carlo variance falls as 1/spp, so reaching the other's error takes rmse-ratio^2
    # times the samples: efficiency (1 / (variance x time)) ratio = speed ratio / rmse ratio^2.
    for label, key, speed in (("default", "tray", tray_sobol), ("jitter", "tray_jitter", tray)):
        for name, m in (("llvm_ad_rgb", mi_llvm), ("scalar_rgb", mi_scalar)):
            q = (rmse[key] / rmse[name]) ** 2
            say(f"  time to equal error, Mitsuba {name} / TRay ({label}): "
                f"{speed[0] / m[0] / q:.2f} (wall clock), {speed[1] / m[1] / q:.2f} (per CPU-second)")
    for smp, m in mi_better.items():
        q = (rmse["tray"] / rmse[smp]) ** 2
        say(f"  time to equal error, Mitsuba llvm_ad_rgb {smp} / TRay (default): "
            f"{tray_sobol[0] / m[0] / q:.2f} (wall clock), {tray_sobol[1] / m[1] / q:.2f} "
            "(per CPU-second)")

    if a.report:
        with open(a.report, "w") as f:
            f.write("\n".join(LINES) + "\n")


if __name__ == "__main__":
    main()
