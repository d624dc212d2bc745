"""Speed measurements and the equal-error arithmetic of bench/mitsuba_compare.py, shared by its
Cornell box and heavier-scene sections (bench/mitsuba_heavy.py)."""
import re
import subprocess
import time

import drjit as dr
import mitsuba as mi

from compare_report import fail, say

# Mitsuba 3's samplers that stratify (its default, `independent`, does not).
MITSUBA_STRATIFIED = ("stratified", "ldsampler")


def mitsuba_render(scene, spp, seed):
    img = mi.render(scene, spp=spp, seed=seed)
    dr.eval(img)
    dr.sync_thread()  # the llvm variant renders asynchronously: wait before stopping the clock
    return img


def mitsuba_speed(variant, size, spp, depth, repeats, sampler, make_scene):
    """Best of `repeats` renders of make_scene(size, spp, depth, sampler) after a warm-up:
    (Msamples/s, Msamples per CPU-second)."""
    mi.set_variant(variant)
    scene = make_scene(size, spp, depth, sampler)
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
    """Best of `repeats` path_bench runs of `path-scalar` and of `path` (the wavefront; path_bench
    measures both in each run, in that order): per integrator a dict of Msamples/s (`wall`),
    Msamples per CPU-second (`cpu`), Mrays per CPU-second (`rays`) and, for the wavefront, the
    share of its time in batched traversal (`traversal`, from the fastest run)."""
    best = [{"wall": 0.0, "cpu": 0.0, "rays": 0.0, "traversal": -1.0} for _ in range(2)]
    for _ in range(repeats):
        r = subprocess.run([bench, gltf, str(threads), str(size), str(spp), "--sampler", sampler,
                            "--no-replay", "--no-error"], capture_output=True, text=True)
        if r.returncode != 0:
            fail(f"{bench} failed (exit {r.returncode}): {r.stderr.strip() or r.stdout.strip()}")
        wall = re.findall(r"Msamples/s\s+([0-9.]+)", r.stdout)
        cpu = re.findall(r"([0-9.]+) Msamples per CPU-second", r.stdout)
        rays = re.findall(r"([0-9.]+) Mrays per CPU-second", r.stdout)
        traversal = re.findall(r"traversal\s+([0-9.]+)% of the render", r.stdout)
        if len(wall) < 2 or len(cpu) < 2 or len(rays) < 2 or not traversal:
            fail(f"{bench}: expected 'Msamples/s', 'Msamples per CPU-second', 'Mrays per "
                 f"CPU-second' for path-scalar and path, and the wavefront's traversal share:\n{r.stdout}")
        for k, b in enumerate(best):
            if float(cpu[k]) > b["cpu"]:
                b.update(cpu=float(cpu[k]), rays=float(rays[k]),
                         traversal=float(traversal[0]) if k == 1 else -1.0)
            b["wall"] = max(b["wall"], float(wall[k]))
    for label, b in zip((" scalar", ""), best):
        share = f", traversal {b['traversal']:.0f}%" if b["traversal"] >= 0 else ""
        say(f"  TRay{label:10s} {sampler:12s} best {size * size * spp / b['wall'] * 1e-6:7.2f} s  "
            f"{b['wall']:7.3f} Msamples/s  {b['cpu']:7.3f} per CPU-s  ({threads} threads; "
            f"{b['rays']:.2f} Mrays per CPU-s{share})")
    return best


def equal_error_lines(mi_speed, mi_err, tray_speeds, tray_err):
    """Time to equal error, Mitsuba's / TRay's, per CPU-second: Monte Carlo variance falls as
    1/spp, so reaching the other's error takes rmse-ratio^2 times the samples, and the
    efficiency (1 / (variance x time)) ratio is speed ratio / rmse ratio^2. `tray_speeds`:
    (label, tray_speed result, key of tray_err); Mitsuba's: by sampler or variant name."""
    for label, speed, key in tray_speeds:
        for k, integrator in enumerate(("path-scalar", "path")):
            cells = []
            for name, m in mi_speed.items():
                q = (tray_err[key] / mi_err[name]) ** 2
                cells.append(f"{name} {speed[k]['cpu'] / m[1] / q:.2f}")
            say(f"  time to equal error, Mitsuba / TRay {integrator} ({label}), per CPU-second: "
                + ", ".join(cells))
