#!/usr/bin/env python3
"""Mitsuba 3's error against CPU time on the Cornell box (issue 37's charts): for each sampler
and spp, one warm-up render (the llvm variant's JIT compilation excluded), then one timed
render (process CPU seconds, Dr.Jit's threads on every core: set to one thread, Dr.Jit 1.5
deadlocks while loading the scene), its RMSE against the converged reference. One line per
render on standard output: `mitsuba <sampler> <spp> <cpu seconds> <rmse>`.
bench/cornell_error_vs_time.py runs it and puts its points beside TRay's and Cycles'.

Usage (tools/setup-mitsuba.sh's venv, DRJIT_LIBLLVM_PATH as tools/compare-mitsuba.sh sets it):
  build/mitsuba-venv/bin/python bench/mitsuba_cornell_curve.py [--size 256] [--spp 16,64,256]
      [--samplers independent,ldsampler] [--max-depth 8]
"""
import argparse
import os
import time

import mitsuba as mi
import numpy as np

from compare_report import rmse
from mitsuba_compare import SHARED, mitsuba_scene, read_rgb
from mitsuba_measure import mitsuba_render


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--spp", default="16,64,256")
    p.add_argument("--samplers", default="independent,ldsampler")
    p.add_argument("--max-depth", type=int, default=8)
    p.add_argument("--reference", default=os.path.join(SHARED, "cornell-box.ref.exr"))
    a = p.parse_args()
    mi.set_variant("llvm_ad_rgb")
    ref = read_rgb(a.reference)
    for sampler in a.samplers.split(","):
        for spp in (int(s) for s in a.spp.split(",")):
            scene = mitsuba_scene(a.size, spp, a.max_depth, sampler)
            mitsuba_render(scene, spp, 0)  # warm-up: JIT compilation, first-touch allocations
            start = time.process_time()
            img = mitsuba_render(scene, spp, 1)
            cpu = time.process_time() - start
            img = np.array(img, dtype=np.float64)[:, :, :3]
            err = rmse(img, ref)
            print(f"mitsuba {sampler} {spp} {cpu:.4f} {err:.6f}", flush=True)


if __name__ == "__main__":
    main()
