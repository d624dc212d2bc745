#!/usr/bin/env python3
"""Russian roulette (--rr-depth, --rr-survival) against efficiency: for each variant, the
variance of a render's pixels and its CPU time, on one thread, the variants' renders taken in
turn (pair k of every variant, then pair k + 1). The variance of an unbiased image needs no
reference: two renders with other seeds differ by twice it, pixel by pixel ((a - b)^2 / 2).
Two means over the image: the variance itself (what RMSE weighs) and the relative variance
without the 0.1% worst pixels (divided by m^2 + 0.01, m the pair's mean, as relMSE weighs
error; one sun glint can decide a whole image's variance). Efficiency = 1 / (variance x render
CPU seconds, tray:renderCpuSeconds), relative to the first variant listed. With --by-max-depth,
also the variance by --max-depth: where the noise comes from (1 = emitters seen directly,
2 = plus direct light, ...).

Usage: /usr/bin/python3 bench/roulette_sweep.py SCENE [--build build] [--spp 64] [--size 256]
           [--variants "--rr-depth 5;--rr-depth 3;--rr-survival sqrt"] [--pairs 2]
           [--by-max-depth 1,2,3,4,5,6,8]"""
import argparse
import os
import subprocess
import tempfile

import numpy as np
import OpenImageIO as oiio


def render(a, tmp, seed, extra):
    out = os.path.join(tmp, f"s{seed}.exr")
    cmd = [os.path.join(a.build, "tray-render"), "--integrator", "path", "--spp", str(a.spp),
           "--threads", "1", "--seed", str(seed), "--resolution", f"{a.size}x{a.size}",
           "--allow-any-path", "--float", *extra, a.scene, "-o", out]
    subprocess.run(cmd, check=True, capture_output=True,
                   env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
    i = oiio.ImageInput.open(out)
    pixels = i.read_image(format="float")[..., :3]
    cpu = i.spec().getattribute("tray:renderCpuSeconds")
    i.close()
    return pixels, cpu


def pair(a, tmp, k, extra):
    """Variance, trimmed relative variance and the two CPU times of the k-th pair of seeds."""
    (x, cx), (y, cy) = render(a, tmp, 2 * k + 1, extra), render(a, tmp, 2 * k + 2, extra)
    per_pixel = np.mean((x - y) ** 2, axis=2) / 2
    rel = np.sort((per_pixel / (np.mean((x + y) / 2, axis=2) ** 2 + 0.01)).ravel())
    return float(np.mean(per_pixel)), float(np.mean(rel[:len(rel) - len(rel) // 1000])), [cx, cy]


def measure(a, tmp, variants):
    """Per variant: mean variance, trimmed relative variance and CPU seconds over a.pairs."""
    sums = [([], [], []) for _ in variants]
    for k in range(a.pairs):
        for v, extra in enumerate(variants):
            var, rel, cpu = pair(a, tmp, k, extra)
            sums[v][0].append(var), sums[v][1].append(rel), sums[v][2].extend(cpu)
    return [tuple(float(np.mean(x)) for x in s) for s in sums]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scene")
    p.add_argument("--build", default="build")
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--variants", default="--rr-depth 5;--rr-depth 2;--rr-depth 3;--rr-depth 4;"
                   "--rr-depth 6;--rr-depth 8;--rr-survival sqrt")
    p.add_argument("--pairs", type=int, default=2)
    p.add_argument("--by-max-depth", default="")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        print(f"{a.scene}: {a.size}x{a.size}, {a.spp} spp, 1 thread, {a.pairs} pairs of seeds")
        variants = [v.split() for v in a.variants.split(";")]
        print(f"{'variant':<34} CPU s  variance    efficiency  rel. var. trimmed  efficiency")
        first = None
        for extra, (var, rel, cpu) in zip(variants, measure(a, tmp, variants)):
            eff = (1 / (var * cpu), 1 / (rel * cpu))
            first = first or eff
            print(f"{' '.join(extra):<32} {cpu:6.3f}  {var:.4e}  {eff[0] / first[0]:10.3f}  "
                  f"{rel:.4e}         {eff[1] / first[1]:10.3f}")
        if a.by_max_depth:
            depths = a.by_max_depth.split(",")
            print("max-depth   CPU s  variance    rel. var. trimmed")
            for d, (var, rel, cpu) in zip(depths, measure(a, tmp, [["--max-depth", d]
                                                                      for d in depths])):
                print(f"{d:>9}  {cpu:6.3f}  {var:.4e}  {rel:.4e}")


if __name__ == "__main__":
    main()
