#!/usr/bin/env python3
"""Renders every sample scene twice and checks that the two renders have the same pixels, bit
for bit (every channel of every layer, AOVs included).

The two renders differ by what you name: two integrators of one build (`path` against its
reference `path-scalar`: the SIMD stages must give the scalar estimator's bits) or two builds
(a change that must not move a pixel, or a build with -march=native against the default one).

  tools/same-pixels.py --a build/tray-render --ia path --ib path-scalar
  tools/same-pixels.py --a old/tray-render --b build/tray-render --ia path

Scenes: the shared Khronos samples (../shared/gltf-samples, ../shared/gltf-features), the
shared reference scenes and scenes/*.gltf. Exit 1 when any scene differs (each is named, with
the number of values that differ), 0 when all match.
"""
import argparse
import glob
import os
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(os.path.dirname(ROOT), "shared")


def sample_scenes():
    found = []
    for folder in ("gltf-samples", "gltf-features", "reference"):
        base = os.path.join(SHARED, folder)
        for ext in ("gltf", "glb"):
            found += glob.glob(os.path.join(base, "*." + ext))
            found += glob.glob(os.path.join(base, "*", "*." + ext))
            found += glob.glob(os.path.join(base, "*", "glTF", "*." + ext))
    found += glob.glob(os.path.join(ROOT, "scenes", "*.gltf"))
    return sorted(p for p in set(found) if "/invalid/" not in p)


# Every layer but the light paths, spelled out: what `--aov all` meant before it took in the
# light paths (with path), so that builds from before and after compare.
AOVS = "depth,normal,position,albedo,objectid,materialid,samples,motion,cryptomatte"


def render(binary, integrator, scene, out, args):
    cmd = [binary, "--integrator", integrator, scene, "-o", out, "--float", "-q",
           "--resolution", args.resolution, "--spp", str(args.spp), "--aov", args.aov,
           "--threads", str(args.threads)] + args.extra
    r = subprocess.run(cmd, capture_output=True, text=True)
    return r.returncode, r.stderr.strip().splitlines()[-1:] if r.returncode else []


def pixels(path):
    image = oiio.ImageInput.open(path)
    layers = []
    subimage = 0
    while image.seek_subimage(subimage, 0):
        layers.append(image.read_image(format="float"))
        subimage += 1
    image.close()
    return layers


def differing(a, b):
    if len(a) != len(b):
        return -1
    count = 0
    for x, y in zip(a, b):
        if x.shape != y.shape:
            return -1
        # Bit patterns, so that NaN == NaN and -0 != +0.
        count += int(np.count_nonzero(x.view(np.uint32) != y.view(np.uint32)))
    return count


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--a", default=os.path.join(ROOT, "build", "tray-render"))
    p.add_argument("--b", help="second binary (default: the first)")
    p.add_argument("--ia", default="path", help="integrator of the first render")
    p.add_argument("--ib", help="integrator of the second render (default: the first's)")
    p.add_argument("--resolution", default="64x48")
    p.add_argument("--spp", type=int, default=4)
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--scene", action="append", help="only these scenes (default: all)")
    p.add_argument("--aov", default=AOVS, help="the layers compared (default: all but the light paths)")
    p.add_argument("extra", nargs="*", help="more tray-render options, after --")
    args = p.parse_args()
    args.b = args.b or args.a
    args.ib = args.ib or args.ia
    scenes = args.scene or sample_scenes()
    bad = 0
    with tempfile.TemporaryDirectory(prefix="tray_same_pixels_") as tmp:
        for i, scene in enumerate(scenes):
            name = os.path.relpath(scene, os.path.dirname(ROOT))
            out_a, out_b = os.path.join(tmp, f"{i}a.exr"), os.path.join(tmp, f"{i}b.exr")
            rc_a, err_a = render(args.a, args.ia, scene, out_a, args)
            rc_b, err_b = render(args.b, args.ib, scene, out_b, args)
            if rc_a or rc_b:
                same = rc_a == rc_b
                print(f"{'same' if same else 'DIFFERENT'} {name}: exit {rc_a} / {rc_b} {err_a}")
                bad += not same
                continue
            n = differing(pixels(out_a), pixels(out_b))
            print(f"{'same' if n == 0 else 'DIFFERENT'} {name}" +
                  ("" if n == 0 else f": {n} values differ" if n > 0 else ": layers differ"))
            bad += n != 0
    print(f"{len(scenes) - bad} of {len(scenes)} scenes identical")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
