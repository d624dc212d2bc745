"""The heavier scenes of bench/mitsuba_compare.py (issue 16): scenes/bench/heavy-helmets.gltf
(DamagedHelmet and WaterBottle, textured, on a glossy metal floor with a glass sphere, sky and
area light) and scenes/bench/heavy-spheres.gltf (MetalRoughSpheresNoTextures, ~1M triangles, under a
white sky). Mitsuba renders each from the same glTF through bench/gltf_to_mitsuba.py.

Per scene, in one run:
1. Accuracy: converged renders of both (Mitsuba llvm_ad_rgb, TRay's default `path`, each at
   --heavy-ref-spp, cached in --ref-cache), channel means side by side and a PNG.
2. Error at equal spp: each configuration's RMSE against its own renderer's converged render
   (their material models differ slightly, so not pixel against pixel across renderers).
3. Speed per CPU-second: Mitsuba llvm_ad_rgb (independent, stratified, ldsampler) and
   scalar_rgb, warm-up excluded; TRay's path_bench (`path-scalar` and `path`, the wavefront).
4. Ratios TRay / Mitsuba per sample and to equal error.
"""
import hashlib
import json
import os
import shutil
import subprocess
import tempfile

import mitsuba as mi
import numpy as np

import gltf_to_mitsuba as g2m
from compare_report import channel_means, check_image, cpu_of, fail, rmse, say
from mitsuba_measure import (MITSUBA_STRATIFIED, equal_error_lines, mitsuba_render,
                             mitsuba_speed, whole_render_equal_error, whole_render_runs,
                             paired_per_sample, tray_speed)

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = ("heavy-helmets", "heavy-spheres")
# (variant, sampler) of the Mitsuba configurations, keyed as equal_error_lines names them.
MITSUBA_RUNS = {"llvm_ad_rgb": ("llvm_ad_rgb", "independent"),
                "scalar_rgb": ("scalar_rgb", "independent"),
                **{s: ("llvm_ad_rgb", s) for s in MITSUBA_STRATIFIED}}


def add_arguments(p):
    g = p.add_argument_group("heavier scenes")
    g.add_argument("--heavy-size", type=int, default=128, help="speed runs: image size")
    g.add_argument("--heavy-spp", type=int, default=64, help="speed runs: samples per pixel")
    g.add_argument("--heavy-error-size", type=int, default=128,
                   help="size of the converged renders and of the equal-spp error renders")
    g.add_argument("--heavy-error-spp", type=int, default=16)
    g.add_argument("--heavy-ref-spp", type=int, default=1024,
                   help="samples per pixel of the converged renders")
    g.add_argument("--mean-tolerance", type=float, default=2.0,
                   help="allowed difference of the converged renders' channel means, percent")
    g.add_argument("--ref-cache", default=os.path.join(HERE, "..", "build", "mitsuba-refs"),
                   help="folder for the converged renders (kept between runs)")
    g.add_argument("--side-by-side", help="write the converged renders here as a PNG")


def quick(a):
    # 16 spp: Mitsuba's stratified and ldsampler want a power of two that is a square.
    a.heavy_size, a.heavy_spp, a.heavy_error_size = 64, 16, 64
    a.heavy_error_spp, a.heavy_ref_spp = 16, 256


def stage(path, folder):
    """A copy of the scene in `folder` with its buffers and images beside it: path_bench loads
    files only from the scene's own folder (no --allow-any-path)."""
    with open(path) as f:
        doc = json.load(f)
    for kind in ("buffers", "images"):
        for i, item in enumerate(doc.get(kind, [])):
            uri = item.get("uri", "")
            if uri and not uri.startswith("data:"):
                local = f"{kind}{i}-{os.path.basename(uri)}"
                shutil.copyfile(os.path.join(os.path.dirname(path), uri),
                                os.path.join(folder, local))
                item["uri"] = local
    out = os.path.join(folder, os.path.basename(path))
    with open(out, "w") as f:
        json.dump(doc, f)
    return out


def tray_image(a, scene, size, spp, extra, tmp):
    out = os.path.join(tmp, "tray.exr")
    if os.path.exists(out):
        os.remove(out)
    cmd = [a.tray_render, "--spp", str(spp), "--max-depth", str(a.max_depth), "--resolution",
           f"{size}x{size}", "--float", "--threads", str(a.threads), *extra, scene, "-o", out]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0 or not os.path.exists(out):
        fail(f"{' '.join(cmd)} failed (exit {r.returncode}): {r.stderr.strip()}")
    return np.array(mi.Bitmap(out), dtype=np.float64)[:, :, :3]


def whole(a, scene, size, extra, tmp):
    """One tray-render of the path tracer: (image, CPU seconds of the whole run)."""
    out = os.path.join(tmp, "whole.exr")
    cpu = cpu_of([a.tray_render, "--integrator", "path", "--max-depth", str(a.max_depth),
                  "--resolution", f"{size}x{size}", "--float", "--threads", str(a.threads),
                  *extra, scene, "-o", out])
    return np.array(mi.Bitmap(out), dtype=np.float64)[:, :, :3], cpu


def mitsuba_image(gltf, run, size, spp, depth, seed):
    mi.set_variant(run[0])
    scene = mi.load_dict(g2m.scene_dict(gltf, (size, size), spp, depth, run[1]))
    return np.array(mitsuba_render(scene, spp, seed), dtype=np.float64)[:, :, :3]


def cached(a, key, make):
    """A converged render from the cache, or made and stored there."""
    os.makedirs(a.ref_cache, exist_ok=True)
    path = os.path.join(a.ref_cache, key + ".npy")
    if os.path.exists(path):
        return np.load(path)
    img = make()
    np.save(path, img)
    return img


def accuracy(a, name, gltf, staged, tmp):
    """Converged renders of both, their channel means compared; returns (mitsuba, tray, ok)."""
    size, spp = a.heavy_error_size, a.heavy_ref_spp
    with open(gltf.path, "rb") as f:
        tag = f"{name}-{hashlib.sha256(f.read()).hexdigest()[:10]}-{size}-{spp}-d{a.max_depth}"
    mi_ref = cached(a, tag + "-mitsuba", lambda: mitsuba_image(
        gltf, MITSUBA_RUNS["llvm_ad_rgb"], size, spp, a.max_depth, 0))
    # Seed 1: the equal-spp renders use seed 0, so their samples are not among the reference's.
    tr_ref = cached(a, tag + "-tray", lambda: tray_image(
        a, staged, size, spp, ["--integrator", "path", "--seed", "1"], tmp))
    check_image("Mitsuba converged", mi_ref, tr_ref.shape)
    check_image("TRay converged", tr_ref, mi_ref.shape)
    m, t = channel_means(mi_ref), channel_means(tr_ref)
    rel = (t / m - 1) * 100
    ok = bool(np.all(np.abs(rel) <= a.mean_tolerance))
    say(f"Accuracy: {size}x{size}, {spp} spp, Mitsuba llvm_ad_rgb against TRay path (default)")
    say(f"  means Mitsuba R {m[0]:.5f} G {m[1]:.5f} B {m[2]:.5f}, TRay R {t[0]:.5f} G {t[1]:.5f} "
        f"B {t[2]:.5f}: TRay {rel[0]:+.2f}% {rel[1]:+.2f}% {rel[2]:+.2f}% "
        f"({'within' if ok else 'OUTSIDE'} the {a.mean_tolerance:g}% tolerance); RMSE between "
        f"them {rmse(tr_ref, mi_ref):.5f}")
    return mi_ref, tr_ref, ok


def equal_spp_errors(a, gltf, staged, mi_ref, tr_ref, tmp):
    size, spp = a.heavy_error_size, a.heavy_error_spp
    say(f"Error: {size}x{size}, {spp} spp, RMSE against the renderer's own converged render")
    err = {}
    for key, run in MITSUBA_RUNS.items():
        img = mitsuba_image(gltf, run, size, spp, a.max_depth, 1)
        check_image(f"Mitsuba {key}", img, mi_ref.shape)
        err[key] = rmse(img, mi_ref)
        say(f"  Mitsuba {' '.join(run):28s} RMSE {err[key]:.5f}")
    for key, label, extra in (("tray", "path (default)", []),
                              ("tray_jitter", "path --sampler independent",
                               ["--sampler", "independent"])):
        img = tray_image(a, staged, size, spp, ["--integrator", "path", *extra], tmp)
        check_image(f"TRay {label}", img, tr_ref.shape)
        err[key] = rmse(img, tr_ref)
        say(f"  TRay {label:31s} RMSE {err[key]:.5f}")
        if key == "tray":
            scalar = tray_image(a, staged, size, spp, ["--integrator", "path-scalar"], tmp)
            same = int(np.sum(np.any(scalar != img, axis=2)))
            say(f"  TRay path-scalar (default sampler): {same} of {size * size} pixels differ "
                "from path's (same random numbers, so the same error)")
    return err


def speed(a, gltf, staged):
    size, spp = a.heavy_size, a.heavy_spp
    say(f"Speed: {size}x{size}, {spp} spp, max depth {a.max_depth}, best of {a.repeats}")
    make = lambda s, n, d, smp: mi.load_dict(g2m.scene_dict(gltf, (s, s), n, d, smp))
    mi_speed = {key: mitsuba_speed(run[0], size, spp, a.max_depth, a.repeats, run[1], make)
                for key, run in MITSUBA_RUNS.items()}
    tray = tray_speed(a.tray_bench, staged, a.threads, size, spp, a.repeats, "independent")
    tray_sobol = tray_speed(a.tray_bench, staged, a.threads, size, spp, a.repeats, "sobol")
    for name in ("llvm_ad_rgb", "scalar_rgb"):
        m = mi_speed[name]
        say(f"  per sample, TRay independent / Mitsuba {name:12s}: path-scalar "
            f"{tray[0]['cpu'] / m[1]:.2f}, path {tray[1]['cpu'] / m[1]:.2f} (per CPU-second)")
    paired_per_sample(size, spp, a.max_depth, a.paired_rounds, make, a.tray_bench, staged,
                      a.threads)
    say(f"  (load at the end of the speed runs: {os.getloadavg()[0]:.2f})")
    return mi_speed, tray, tray_sobol


def side_by_side(path, rows):
    """Rows of (Mitsuba, TRay) converged renders, tone mapped by clipping, as an sRGB PNG."""
    width = max(m.shape[1] + t.shape[1] for m, t in rows)
    grid = np.concatenate([np.pad(np.concatenate([t, m], 1),
                                  ((0, 0), (0, width - m.shape[1] - t.shape[1]), (0, 0)))
                           for m, t in rows], 0)
    bmp = mi.Bitmap(np.clip(grid, 0, 1).astype(np.float32), mi.Bitmap.PixelFormat.RGB)
    bmp.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, True).write(path)


def run(a):
    """All heavier scenes; False if a pair of converged renders disagrees in its means."""
    rows, all_ok = [], True
    for name in SCENES:
        path = os.path.join(HERE, "..", "scenes", "bench", name + ".gltf")
        try:
            gltf = g2m.Gltf(path)
            mi.set_variant("llvm_ad_rgb")
            g2m.scene_dict(gltf, (8, 8), 1, 1)  # convert once, to fail before measuring
        except (OSError, g2m.ConversionError) as e:
            fail(f"{path}: {e}")
        say()
        say(f"== {name} ({os.path.relpath(path, os.getcwd())})")
        with tempfile.TemporaryDirectory() as tmp:
            staged = stage(path, tmp)
            mi_ref, tr_ref, ok = accuracy(a, name, gltf, staged, tmp)
            all_ok = all_ok and ok
            rows.append((mi_ref, tr_ref))
            err = equal_spp_errors(a, gltf, staged, mi_ref, tr_ref, tmp)
            mi_speed, tray, tray_sobol = speed(a, gltf, staged)
            equal_error_lines(mi_speed, err, (("default", tray_sobol, "tray"),
                                              ("independent, jitter", tray, "tray_jitter")), err)
            say("Whole renders, TRay uniform and adaptive (issue 37), against TRay's converged "
                "render:")
            size, spp = a.heavy_error_size, a.heavy_error_spp
            runs = whole_render_runs(lambda extra: whole(a, staged, size, extra, tmp),
                                     lambda img: rmse(img, tr_ref), spp)
            whole_render_equal_error(mi_speed, err, size * size, spp, runs)
    if a.side_by_side:
        side_by_side(a.side_by_side, rows)
        say(f"\nConverged renders, TRay left, Mitsuba right: {a.side_by_side}")
    return all_ok
