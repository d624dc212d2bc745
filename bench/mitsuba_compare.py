#!/usr/bin/env python3
"""TRay's path tracer against Mitsuba 3, both measured in this run on this machine.

Speed: Mitsuba's Cornell box (mi.cornell_box(), path max_depth 8, box filter, independent
sampler) at --size/--spp in the llvm_ad_rgb and scalar_rgb variants (one warm-up render so JIT
compilation is excluded, then best of --repeats), and TRay's path_bench on the same scene as glTF
(best of --repeats). Error: both at the reference's 256x256 and --error-spp against Mitsuba's
converged render (/work/shared/reference/cornell-box.ref.exr); TRay with its default (Sobol'
numbers, jittered pixel positions), with independent numbers, and independent throughout like
Mitsuba's independent sampler. TRay's figures cover both `path-scalar` and `path` (the wavefront driver).
Then the heavier scenes (bench/mitsuba_heavy.py): scenes/bench/heavy-*.gltf, converted for
Mitsuba by bench/gltf_to_mitsuba.py. --quick: small sizes and one repeat, a few minutes in all.

Run with the venv of tools/setup-mitsuba.sh (tools/compare-mitsuba.sh does it all).
"""
import argparse
import os
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

import mitsuba_heavy
from compare_report import LINES, check_image, cpu_of, fail, rmse, say
from mitsuba_measure import (MITSUBA_STRATIFIED, equal_error_lines, mitsuba_render,
                             mitsuba_speed, paired_per_sample, tray_speed,
                             whole_render_equal_error, whole_render_runs)

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.normpath(os.path.join(HERE, "..", "..", "shared", "reference"))


def mitsuba_scene(size, spp, depth, sampler="independent"):
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = size
    d["sensor"]["film"]["height"] = size
    d["sensor"]["film"]["rfilter"] = {"type": "box"}
    d["sensor"]["sampler"] = {"type": sampler, "sample_count": spp}
    d["integrator"] = {"type": "path", "max_depth": depth}
    return mi.load_dict(d)


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


def cornell_whole(a, tmp, shape, extra):
    """One tray-render of the Cornell box at the reference's size, TRay's threads: (image, CPU
    seconds of the whole run)."""
    out = os.path.join(tmp, "whole.exr")
    cmd = [a.tray_render, "--integrator", "path", "--max-depth", str(a.max_depth), "--resolution",
           f"{shape[1]}x{shape[0]}", "--float", "--threads", str(a.threads), *extra, a.gltf,
           "-o", out]
    cpu = cpu_of(cmd)
    return read_rgb(out), cpu


def report_error(name, img, ref):
    check_image(name, img, ref.shape)
    e = rmse(img, ref)
    means = img.reshape(-1, 3).mean(axis=0)
    rel = (means / ref.reshape(-1, 3).mean(axis=0) - 1) * 100
    say(f"  {name:24s} RMSE {e:.5f}  means R {means[0]:.5f} G {means[1]:.5f} B {means[2]:.5f}"
        f"  ({rel[0]:+.2f}% {rel[1]:+.2f}% {rel[2]:+.2f}%)")
    return e


def cornell_speed(a):
    say(f"Speed: {a.size}x{a.size}, {a.spp} spp, max depth {a.max_depth}, best of {a.repeats}")
    run = lambda variant, smp: mitsuba_speed(variant, a.size, a.spp, a.max_depth, a.repeats,
                                             smp, mitsuba_scene)
    mi_speed = {"llvm_ad_rgb": run("llvm_ad_rgb", "independent"),
                "scalar_rgb": run("scalar_rgb", "independent")}
    # Mitsuba's own stratified samplers, for a best-against-best comparison at equal error.
    for smp in MITSUBA_STRATIFIED:
        mi_speed[smp] = run("llvm_ad_rgb", smp)
    # Per sample, like for like: TRay's independent sequence; its default, Sobol', costs more
    # per sample and is worth more (the error section).
    tray = tray_speed(a.tray_bench, a.gltf, a.threads, a.size, a.spp, a.repeats, "independent")
    tray_sobol = tray_speed(a.tray_bench, a.gltf, a.threads, a.size, a.spp, a.repeats, "sobol")
    for name in ("llvm_ad_rgb", "scalar_rgb"):
        m = mi_speed[name]
        say(f"  TRay independent / Mitsuba {name:12s} {tray[0]['wall'] / m[0]:.2f} (wall clock), "
            f"{tray[0]['cpu'] / m[1]:.2f} (per CPU-second) with path-scalar; path (wavefront) "
            f"{tray[1]['wall'] / m[0]:.2f}, {tray[1]['cpu'] / m[1]:.2f}")
    paired_per_sample(a.size, a.spp, a.max_depth, a.paired_rounds, mitsuba_scene, a.tray_bench,
                      a.gltf, a.threads)
    say(f"  (load at the end of the speed runs: {os.getloadavg()[0]:.2f}; per CPU-second figures"
        " depend less on other jobs)")
    return mi_speed, tray, tray_sobol


def cornell_error(a):
    ref = read_rgb(a.reference)
    size = ref.shape[1]
    m = ref.reshape(-1, 3).mean(axis=0)
    say()
    say(f"Error: {size}x{ref.shape[0]}, {a.error_spp} spp (Mitsuba: independent sampler), against "
        f"{os.path.basename(a.reference)} (means R {m[0]:.5f} G {m[1]:.5f} B {m[2]:.5f})")
    err = {}
    for variant in ("llvm_ad_rgb", "scalar_rgb"):
        mi.set_variant(variant)
        img = mitsuba_render(mitsuba_scene(size, a.error_spp, a.max_depth), a.error_spp, 1)
        err[variant] = report_error(f"Mitsuba {variant}", np.array(img, dtype=np.float64), ref)
    mi.set_variant("llvm_ad_rgb")
    for smp in MITSUBA_STRATIFIED:
        img = mitsuba_render(mitsuba_scene(size, a.error_spp, a.max_depth, smp), a.error_spp, 1)
        err[smp] = report_error(f"Mitsuba llvm {smp}", np.array(img, dtype=np.float64), ref)
    res = f"{size}x{ref.shape[0]}"
    with tempfile.TemporaryDirectory() as tmp:
        # TRay's default: Owen-scrambled Sobol' numbers (--sampler sobol), camera rays at the
        # sequence's own 2D points (--pixel-sampler auto = sequence at power-of-two spp).
        err["tray"] = report_error("TRay path (default)", tray_render(a, tmp, res, a.error_spp, []),
                                   ref)
        # Independent numbers, jittered pixel positions (one per stratum of an 8x8 grid).
        img = tray_render(a, tmp, res, a.error_spp, ["--sampler", "independent"])
        err["tray_jitter"] = report_error("TRay path (jitter)", img, ref)
        # Like-for-like with Mitsuba's independent sampler: independent numbers, and camera
        # rays at the sequence's own (then uniform) points.
        img = tray_render(a, tmp, res, a.error_spp,
                          ["--sampler", "independent", "--pixel-sampler", "sequence"])
        err["tray_indep"] = report_error("TRay path (independent)", img, ref)
    for name in ("llvm_ad_rgb", "scalar_rgb"):
        say(f"  RMSE TRay / Mitsuba {name:12s} {err['tray_indep'] / err[name]:.3f} (independent)"
            f", {err['tray_jitter'] / err[name]:.3f} (jitter), {err['tray'] / err[name]:.3f}"
            " (TRay's default)")
    say("  (1 = the same error at equal spp; both renderers are unbiased; path-scalar renders "
        "the same pixels as path, so the same errors)")
    return err


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--tray-build", default=os.path.normpath(os.path.join(HERE, "..", "build")),
                   help="folder with TRay's path_bench and tray-render (default: build/)")
    p.add_argument("--gltf", default=os.path.join(SHARED, "cornell-box.gltf"))
    p.add_argument("--reference", default=os.path.join(SHARED, "cornell-box.ref.exr"))
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--max-depth", type=int, default=8)
    p.add_argument("--threads", type=int, default=2,
                   help="TRay's threads (Mitsuba uses every core: Dr.Jit 1.5 set to one "
                        "thread deadlocks in scene loading; compare per CPU-second)")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--paired-rounds", type=int, default=5,
                   help="rounds of Mitsuba llvm_ad_rgb and TRay back to back, for the per-sample "
                        "ratio within a round (median reported)")
    p.add_argument("--error-spp", type=int, default=64)
    p.add_argument("--report", help="also write the report to this text file")
    p.add_argument("--quick", action="store_true",
                   help="small sizes and one repeat (a smoke run of a few minutes)")
    p.add_argument("--no-cornell", action="store_true", help="only the heavier scenes")
    p.add_argument("--no-heavy", action="store_true", help="only the Cornell box")
    mitsuba_heavy.add_arguments(p)
    a = p.parse_args()
    if a.quick:
        a.size, a.spp, a.repeats, a.error_spp = 128, 16, 1, 16
        a.paired_rounds = 1
        mitsuba_heavy.quick(a)
    a.tray_bench = os.path.join(a.tray_build, "path_bench")
    a.tray_render = os.path.join(a.tray_build, "tray-render")
    for f in (a.tray_bench, a.tray_render, a.gltf, a.reference):
        if not os.path.exists(f):
            fail(f"{f}: not found")
    return a


def main():
    a = parse_args()
    say(f"TRay vs Mitsuba {mi.__version__} (drjit {dr.__version__}), measured "
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} on {os.cpu_count()} cores "
        f"(load {os.getloadavg()[0]:.2f}){', --quick' if a.quick else ''}; TRay {a.threads} "
        f"threads, Mitsuba {dr.thread_count()}")
    if not a.no_cornell:
        say()
        say("== Cornell box")
        mi_speed, tray, tray_sobol = cornell_speed(a)
        err = cornell_error(a)
        mi_err = {"llvm_ad_rgb": err["llvm_ad_rgb"], "scalar_rgb": err["scalar_rgb"],
                  **{s: err[s] for s in MITSUBA_STRATIFIED}}
        equal_error_lines(mi_speed, mi_err, (("default", tray_sobol, "tray"),
                                             ("jitter", tray, "tray_jitter")), err)
        say("Whole renders, TRay uniform and adaptive (issue 37), against the reference:")
        ref = read_rgb(a.reference)
        with tempfile.TemporaryDirectory() as tmp:
            runs = whole_render_runs(lambda extra: cornell_whole(a, tmp, ref.shape, extra),
                                     lambda img: rmse(img, ref), a.error_spp)
        whole_render_equal_error(mi_speed, mi_err, ref.shape[0] * ref.shape[1], a.error_spp, runs)
    accurate = a.no_heavy or mitsuba_heavy.run(a)
    if a.report:
        with open(a.report, "w") as f:
            f.write("\n".join(LINES) + "\n")
    if not accurate:
        fail("the converged renders' channel means differ by more than --mean-tolerance")


if __name__ == "__main__":
    main()
