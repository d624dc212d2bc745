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


def timed_render(scene, spp, seed):
    """One Mitsuba render: (wall-clock seconds, CPU seconds of the process, all of Dr.Jit's
    threads)."""
    t, c = time.perf_counter(), time.process_time()
    mitsuba_render(scene, spp, seed)
    return time.perf_counter() - t, time.process_time() - c


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
        wall, cpu = timed_render(scene, spp, i + 1)
        best, best_cpu = min(best, wall), min(best_cpu, cpu)
    n = size * size * spp * 1e-6
    name = variant if sampler == "independent" else f"{variant} {sampler}"
    say(f"  Mitsuba {name:12s} best {best:7.2f} s  {n / best:7.3f} Msamples/s  "
        f"{n / best_cpu:7.3f} per CPU-s  (warm-up {warm:.2f} s)")
    return n / best, n / best_cpu


def tray_run(bench, gltf, threads, size, spp, sampler):
    """One path_bench run: per integrator (`path-scalar`, then `path`, the wavefront) a dict of
    Msamples/s (`wall`), Msamples per CPU-second (`cpu`), Mrays per CPU-second (`rays`) and,
    for the wavefront, the share of its time in batched traversal (`traversal`; -1 otherwise)."""
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
    return [{"wall": float(wall[k]), "cpu": float(cpu[k]), "rays": float(rays[k]),
             "traversal": float(traversal[0]) if k == 1 else -1.0} for k in range(2)]


def tray_speed(bench, gltf, threads, size, spp, repeats, sampler):
    """Best of `repeats` path_bench runs (tray_run) of `path-scalar` and of `path`; the rays
    and traversal share are the fastest run's."""
    best = [{"wall": 0.0, "cpu": 0.0, "rays": 0.0, "traversal": -1.0} for _ in range(2)]
    for _ in range(repeats):
        for b, run in zip(best, tray_run(bench, gltf, threads, size, spp, sampler)):
            if run["cpu"] > b["cpu"]:
                b.update(cpu=run["cpu"], rays=run["rays"], traversal=run["traversal"])
            b["wall"] = max(b["wall"], run["wall"])
    for label, b in zip((" scalar", ""), best):
        share = f", traversal {b['traversal']:.0f}%" if b["traversal"] >= 0 else ""
        say(f"  TRay{label:10s} {sampler:12s} best {size * size * spp / b['wall'] * 1e-6:7.2f} s  "
            f"{b['wall']:7.3f} Msamples/s  {b['cpu']:7.3f} per CPU-s  ({threads} threads; "
            f"{b['rays']:.2f} Mrays per CPU-s{share})")
    return best


def paired_per_sample(size, spp, depth, rounds, make_scene, bench, gltf, threads):
    """Per sample, like for like, with the host's drift cancelled: `rounds` rounds, each one
    Mitsuba llvm_ad_rgb render and one path_bench run back to back (both with independent
    numbers), and per round TRay's rate over Mitsuba's, per CPU-second. The best-of figures
    compare runs minutes apart, between which this shared host has moved either renderer's
    rate by up to 73%; a ratio within a round sees the same load. Prints and returns the
    wavefront's ratios (median, then all)."""
    mi.set_variant("llvm_ad_rgb")
    scene = make_scene(size, spp, depth, "independent")
    mitsuba_render(scene, spp, 0)  # warm-up, as mitsuba_speed
    n = size * size * spp * 1e-6
    ratios = []
    for i in range(rounds):
        mitsuba_cpu = n / timed_render(scene, spp, i + 1)[1]
        tray = tray_run(bench, gltf, threads, size, spp, "independent")
        ratios.append(tray[1]["cpu"] / mitsuba_cpu)
    median = sorted(ratios)[len(ratios) // 2]
    say(f"  per sample, paired rounds (Mitsuba llvm_ad_rgb, then TRay path; independent): TRay / "
        f"Mitsuba per CPU-second median {median:.2f} of {rounds} ("
        + " ".join(f"{r:.2f}" for r in ratios) + ")")
    return median, ratios


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


# TRay's noise-driven adaptive sampling (docs/adaptive-sampling.md) at these thresholds, at most
# 4x the error spp: whole renders, timed as such (issue 37).
ADAPTIVE_THRESHOLDS = ("0.1", "0.05", "0.03")
# --noise-metric absolute (RMSE's own measure: the rule then minimises RMSE for the samples
# spent), thresholds in radiance units for images of mean radiance about 0.1-0.5.
ABSOLUTE_THRESHOLDS = ("0.01", "0.007", "0.005")


def whole_render_runs(render, error_of, error_spp):
    """TRay's uniform default and its adaptive sampling measured alike, as whole tray-render
    runs: CPU seconds less a 1-spp run's (scene load and BVH, which Mitsuba's timed renders
    exclude too) and RMSE. render(extra) -> (image, CPU seconds); error_of(image) -> RMSE.
    Returns [(label, CPU seconds, RMSE)]."""
    _, setup = render(["--spp", "1"])
    runs = []
    img, cpu = render(["--spp", str(error_spp)])
    runs.append((f"uniform {error_spp} spp", max(cpu - setup, 1e-3), error_of(img)))
    for t in ADAPTIVE_THRESHOLDS:
        img, cpu = render(["--spp", str(4 * error_spp), "--noise-threshold", t])
        runs.append((f"adaptive {t}", max(cpu - setup, 1e-3), error_of(img)))
    for t in ADAPTIVE_THRESHOLDS:
        img, cpu = render(["--spp", str(4 * error_spp), "--noise-threshold", t,
                           "--noise-decision", "pixel"])
        runs.append((f"adaptive pixel {t}", max(cpu - setup, 1e-3), error_of(img)))
    for t in ABSOLUTE_THRESHOLDS:
        img, cpu = render(["--spp", str(4 * error_spp), "--noise-threshold", t,
                           "--noise-metric", "absolute"])
        runs.append((f"adaptive abs {t}", max(cpu - setup, 1e-3), error_of(img)))
    for label, cpu, e in runs:
        say(f"  TRay path {label:18s} RMSE {e:.5f}  {cpu:7.2f} CPU-s (whole run less setup)")
    return runs


def whole_render_equal_error(mi_speed, mi_err, pixels, error_spp, runs):
    """Time to equal RMSE, Mitsuba's / TRay's, per CPU-second, for whole TRay renders: Mitsuba
    reaches RMSE e in its CPU time for error_spp samples times (its RMSE / e)^2 (its variance
    falls as 1/spp)."""
    for label, cpu, e in runs:
        cells = []
        for name, m in mi_speed.items():
            mitsuba_cpu = pixels * error_spp * 1e-6 / m[1] * (mi_err[name] / e) ** 2
            cells.append(f"{name} {mitsuba_cpu / cpu:.2f}")
        say(f"  time to equal error, Mitsuba / TRay path {label} (whole renders, per "
            "CPU-second): " + ", ".join(cells))
