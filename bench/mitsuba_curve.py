#!/usr/bin/env python3
"""Mitsuba 3's renders for an error-against-time chart (issue 37; bench/error_vs_time.py runs
it): for each sampler and spp, one warm-up render (the llvm variant's JIT compilation excluded),
then --repeats timed renders of seed 1 (process CPU seconds, Dr.Jit's threads on every core:
set to one thread, Dr.Jit 1.5 deadlocks while loading the scene), the least kept. Each timed image is saved as a .npy in --out,
and one line per render goes to standard output: `mitsuba <sampler> <spp> <cpu seconds> <npy>`.
With --reference-spp N it first saves its converged render (seed 1000, not timed) as
`<out>/reference.npy` and prints `reference <npy>`.

The scene: Mitsuba's own Cornell box (`mi.cornell_box()`, the scene the shared reference was
rendered from) for --scene cornell, else the glTF file through bench/gltf_to_mitsuba.py.

Usage (tools/setup-mitsuba.sh's venv, DRJIT_LIBLLVM_PATH as tools/compare-mitsuba.sh sets it):
  build/mitsuba-venv/bin/python bench/mitsuba_curve.py --scene cornell|GLTF --out DIR
      [--size 256] [--spp 16,64,256] [--samplers independent,ldsampler] [--max-depth 8]
      [--reference-spp N] [--repeats N]
"""
import argparse
import os
import time

import mitsuba as mi
import numpy as np

from mitsuba_measure import mitsuba_render


def scene_of(a, spp, sampler):
    if a.scene == "cornell":
        from mitsuba_compare import mitsuba_scene
        return mitsuba_scene(a.size, spp, a.max_depth, sampler)
    import gltf_to_mitsuba as g2m
    return mi.load_dict(g2m.scene_dict(g2m.Gltf(a.scene), (a.size, a.size), spp, a.max_depth,
                                       sampler))


def save(a, name, img):
    path = os.path.join(a.out, name + ".npy")
    np.save(path, np.array(img, dtype=np.float32)[:, :, :3])
    return path


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--scene", required=True, help="cornell, or a glTF file")
    p.add_argument("--out", required=True)
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--spp", default="16,64,256")
    p.add_argument("--samplers", default="independent,ldsampler")
    p.add_argument("--max-depth", type=int, default=8)
    p.add_argument("--reference-spp", type=int, default=0)
    p.add_argument("--repeats", type=int, default=1)
    a = p.parse_args()
    mi.set_variant("llvm_ad_rgb")
    os.makedirs(a.out, exist_ok=True)
    if a.reference_spp:
        img = mitsuba_render(scene_of(a, a.reference_spp, "ldsampler"), a.reference_spp, 1000)
        print(f"reference {save(a, 'reference', img)}", flush=True)
    for sampler in a.samplers.split(","):
        for spp in (int(s) for s in a.spp.split(",")):
            scene = scene_of(a, spp, sampler)
            mitsuba_render(scene, spp, 0)  # warm-up: JIT compilation, first-touch allocations
            cpu = float("inf")
            for _ in range(a.repeats):
                start = time.process_time()
                img = mitsuba_render(scene, spp, 1)
                cpu = min(cpu, time.process_time() - start)
            print(f"mitsuba {sampler} {spp} {cpu:.4f} {save(a, f'{sampler}-{spp}', img)}",
                  flush=True)


if __name__ == "__main__":
    main()
