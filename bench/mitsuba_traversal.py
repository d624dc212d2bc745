"""Where the time of a sample goes, TRay against Mitsuba 3 (issue 16): the same rays traced by
both, then each renderer's samples per CPU-second, so that the traversal part and the rest
(shading, sampling, bookkeeping) of a sample can be told apart.

Per scene, in one run, one thread each (Dr.Jit's pool set to one thread):
1. TRay's bench/batch_bench makes its ray sets with the scene's own camera (`--camera`):
   camera rays row by row, shadow rays from their hits to a point above the scene, cosine-
   distributed bounce rays from the same hits; it times Embree on them (rtcIntersect1 loop and
   rtcIntersect8 packets, the wavefront's default) and writes them out (`--save-rays`).
2. Mitsuba's llvm_ad_rgb variant traces the very same rays (origin moved to tmin: Mitsuba's
   rays have no tmin) in the scene bench/gltf_to_mitsuba.py makes from the same glTF:
   `ray_intersect_preliminary` (closest hit, traversal only; camera rays as `coherent`) and
   `ray_test` (shadow rays), best of --repeats, in Mrays per CPU-second.
3. Both render the scene (max depth 8, independent numbers): Mitsuba's `path`, warm-up
   excluded, best of --repeats; TRay's path_bench (`path-scalar` and `path`, the wavefront, best of
   --repeats), which also prints its rays per sample and the wavefront's measured share of
   time in traversal.
4. From these, per sample: TRay's traversal time (its measured share of the wavefront's time)
   and the rest; then both renderers' traversal time estimated alike, as TRay's rays per sample
   (the same estimator: NEE + MIS, roulette from the fifth segment, so the same expected
   counts) at each renderer's rates from steps 1-2 (camera rates for the first closest hit,
   bounce rates for the others, shadow rates; TRay's packets), and the rest of each sample.

    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 \\
      build/mitsuba-venv/bin/python bench/mitsuba_traversal.py [--tray-build build] [--quick]

Figures only (a benchmark, not a test); docs/bench/mitsuba.md quotes them.
"""
import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile
import time

import drjit as dr
import mitsuba as mi
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gltf_to_mitsuba as g2m  # noqa: E402
from compare_report import fail, say  # noqa: E402
from mitsuba_heavy import stage  # noqa: E402

SHARED = os.path.normpath(os.path.join(HERE, "..", "..", "shared"))
SCENES = {"cornell-box": os.path.join(SHARED, "reference", "cornell-box.gltf"),
          "heavy-helmets": os.path.join(HERE, "..", "scenes", "bench", "heavy-helmets.gltf"),
          "heavy-spheres": os.path.join(HERE, "..", "scenes", "bench", "heavy-spheres.gltf")}
KINDS = ("camera", "shadow", "bounce")


def cpu_seconds():
    r = resource.getrusage(resource.RUSAGE_SELF)  # every thread of the process
    return r.ru_utime + r.ru_stime


def number(pattern, text, what):
    m = re.search(pattern, text)
    if not m:
        fail(f"cannot find {what} in:\n{text}")
    return [float(g) for g in m.groups()]


def tray_traversal(a, scene, folder):
    """batch_bench on the scene's rays, which it saves to `folder`: {mode: [camera, shadow,
    bounce] Mrays per CPU-second}."""
    r = subprocess.run([os.path.join(a.tray_build, "batch_bench"), scene, "--camera", "--size",
                        str(a.size), str(a.size), "--rounds", str(a.repeats), "--save-rays",
                        folder], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"batch_bench failed (exit {r.returncode}): {r.stderr.strip()}")
    rate = r"\s+([0-9.]+) \([ 0-9.]+x\)"
    return {mode: number(re.escape(mode) + rate * 3, r.stdout, mode)
            for mode in ("embree rtcIntersect1 loop", "embree rtcIntersect8")}


def load_rays(path):
    v = np.fromfile(path, dtype=np.float32).reshape(-1, 8)
    o, d, tmin, tmax = v[:, 0:3], v[:, 3:6], v[:, 6], v[:, 7]
    o = o + d * tmin[:, None]  # Mitsuba's rays start at their origin
    tmax = np.minimum(tmax - tmin, np.float32(3.0e38))  # TRay's infinity as a finite maxt
    ray = mi.Ray3f(mi.Point3f(*(mi.Float(o[:, k]) for k in range(3))),
                   mi.Vector3f(*(mi.Float(d[:, k]) for k in range(3))))
    return mi.Ray3f(ray, mi.Float(tmax)), len(v)


def mitsuba_traversal(a, scene, folder, stem):
    """Mitsuba on TRay's saved rays: [camera, shadow, bounce] Mrays per CPU-second."""
    rates = []
    for kind in KINDS:
        ray, n = load_rays(os.path.join(folder, f"{stem}-{kind}.f32"))
        dr.eval(ray)
        best = float("inf")
        for _ in range(a.repeats + 1):  # the first compiles the kernel
            c = cpu_seconds()
            if kind == "shadow":
                out = scene.ray_test(ray)
                count = dr.count(out)
            else:
                pi = scene.ray_intersect_preliminary(ray, coherent=kind == "camera")
                count = dr.count(pi.is_valid())
            dr.eval(count)
            dr.sync_thread()
            best = min(best, cpu_seconds() - c)
        rates.append(n / best * 1e-6)
    return rates


def mitsuba_render_rate(a, scene):
    img = mi.render(scene, spp=a.spp, seed=0)  # warm-up: JIT compilation
    dr.eval(img)
    dr.sync_thread()
    best = float("inf")
    for i in range(a.repeats):
        c = cpu_seconds()
        img = mi.render(scene, spp=a.spp, seed=i + 1)
        dr.eval(img)
        dr.sync_thread()
        best = min(best, cpu_seconds() - c)
    return a.render_size * a.render_size * a.spp / best * 1e-6


def tray_render(a, scene):
    """path_bench, one thread, best of --repeats: Msamples per CPU-second of `path` and
    `path-wavefront`, the wavefront's traversal share, and rays per sample (camera, closest
    after the first, shadow)."""
    best = None
    for _ in range(a.repeats):
        r = subprocess.run([os.path.join(a.tray_build, "path_bench"), scene, "1",
                            str(a.render_size), str(a.spp), "--sampler", "independent",
                            "--no-replay", "--no-error"], capture_output=True, text=True)
        if r.returncode != 0:
            fail(f"path_bench failed (exit {r.returncode}): {r.stderr.strip()}")
        cpu = [float(x) for x in re.findall(r"([0-9.]+) Msamples per CPU-second", r.stdout)]
        share = number(r"traversal\s+([0-9.]+)% of the render", r.stdout, "traversal")[0] / 100
        rays = number(r"camera ([0-9.]+)M, bounce ([0-9.]+)M, shadow ([0-9.]+)M", r.stdout,
                      "ray counts")
        if len(cpu) < 2:
            fail(f"path_bench: no rates in:\n{r.stdout}")
        if best is None or cpu[1] > best["wave"]:
            best = {"path": cpu[0], "wave": cpu[1], "share": share,
                    "per_sample": [x / rays[0] for x in rays]}
        best["path"] = max(best["path"], cpu[0])
    return best


def one_scene(a, name, path, tmp):
    staged = path if name == "cornell-box" else stage(path, tmp)
    say(f"== {name}: {a.size}x{a.size} rays; renders {a.render_size}x{a.render_size}, "
        f"{a.spp} spp, max depth 8, independent numbers; 1 thread each, best of {a.repeats}")
    tray = tray_traversal(a, staged, tmp)
    scene = mi.load_dict(g2m.scene_dict(g2m.Gltf(path), (a.render_size, a.render_size), a.spp, 8))
    mits = mitsuba_traversal(a, scene, tmp, os.path.splitext(os.path.basename(staged))[0])
    say(f"  {'Mrays per CPU-second':34s} {'camera':>8s} {'shadow':>8s} {'bounce':>8s}")
    for mode, r in tray.items():
        say(f"  TRay {mode:29s} {r[0]:8.2f} {r[1]:8.2f} {r[2]:8.2f}")
    say(f"  {'Mitsuba llvm_ad_rgb':34s} {mits[0]:8.2f} {mits[1]:8.2f} {mits[2]:8.2f}")
    packets = tray["embree rtcIntersect8"]
    say(f"  {'TRay packets / Mitsuba':34s} " + " ".join(f"{p / m:7.2f}x"
                                                         for p, m in zip(packets, mits)))
    mi_rate = mitsuba_render_rate(a, scene)
    t = tray_render(a, staged)
    cam, closest, shadow = t["per_sample"]
    tray_us, mi_us = 1 / t["wave"], 1 / mi_rate  # microseconds per sample, one thread
    tray_trav = t["share"] * tray_us
    at_rates = lambda r: cam / r[0] + closest / r[2] + shadow / r[1]  # noqa: E731
    mi_trav, tray_rates = at_rates(mits), at_rates(packets)
    say(f"  render, Msamples per CPU-second: Mitsuba {mi_rate:.3f}, TRay path-scalar "
        f"{t['path']:.3f}, path (wavefront) {t['wave']:.3f} ({t['wave'] / mi_rate:.2f}x Mitsuba)")
    say(f"  rays per sample (TRay's counts): camera {cam:.2f}, closest after it "
        f"{closest:.2f}, shadow {shadow:.2f}")
    say(f"  per sample: TRay {tray_us:.3f} us = traversal {tray_trav:.3f} (measured, "
        f"{100 * t['share']:.0f}%) + rest {tray_us - tray_trav:.3f}; at its packet rates "
        f"traversal ~{tray_rates:.3f} + rest ~{tray_us - tray_rates:.3f}")
    say(f"              Mitsuba {mi_us:.3f} us = traversal ~{mi_trav:.3f} (TRay's rays at "
        f"its rates, ~{100 * mi_trav / mi_us:.0f}%) + rest ~{max(mi_us - mi_trav, 0):.3f}")
    if mi_us > mi_trav:
        say(f"  TRay / Mitsuba, both at their rates: traversal {tray_rates / mi_trav:.1f}x, the "
            f"rest of a sample {(tray_us - tray_rates) / (mi_us - mi_trav):.1f}x")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--tray-build", default=os.path.normpath(os.path.join(HERE, "..", "build")))
    p.add_argument("--size", type=int, default=512, help="ray sets: camera rays per side")
    p.add_argument("--render-size", type=int,
                   help="renders: image side (default: as bench/mitsuba_compare.py, 512 for the "
                   "Cornell box, 128 for the heavier scenes)")
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--scene", action="append", choices=sorted(SCENES),
                   help="repeatable (default: all three)")
    p.add_argument("--quick", action="store_true", help="small sizes, one repeat")
    a = p.parse_args()
    if a.quick:
        a.size, a.render_size, a.spp, a.repeats = 128, 64, 4, 1
    fixed_size = a.render_size
    mi.set_variant("llvm_ad_rgb")
    dr.set_thread_count(1)
    say(f"TRay vs Mitsuba {mi.__version__}: traversal and the rest of a sample, measured "
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} (load "
        f"{os.getloadavg()[0]:.2f})")
    for name in a.scene or SCENES:
        a.render_size = fixed_size or (512 if name == "cornell-box" else 128)
        with tempfile.TemporaryDirectory() as tmp:
            one_scene(a, name, SCENES[name], tmp)


if __name__ == "__main__":
    main()
