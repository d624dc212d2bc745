#!/usr/bin/env python3
"""A diffuse sphere lit only by an environment map, path traced to convergence by TRay and by
Mitsuba 3 (`envmap` emitter): the channel means over the sphere must agree within 0.5%
(issue 14, "Accuracy"). Exit status 1 if they do not.

Scene: camera at the origin looking down -Z (yfov 0.6), a sphere of radius 1 at (0, 0, -4),
Lambertian albedo 0.8 (TRay: glTF metallic 0, roughness 1; Mitsuba: `diffuse`), lit by env_bench's
maps (the windows map and the sun sky) turned --rotate degrees about +Y in both. The mean is over
the pixels TRay's alpha says are fully on the sphere: a disk, symmetric under a horizontal flip,
so the figure does not depend on the two cameras' handedness conventions (the map's orientation
itself is checked direction by direction by bench/envmap_mitsuba_check.py).

Usage (Mitsuba in the venv of tools/setup-mitsuba.sh):
  build/mitsuba-venv/bin/python bench/envmap_mitsuba_lit.py [--build build] [--spp 1024]
"""
import argparse
import json
import math
import os
import subprocess
import sys

try:
    import mitsuba as mi
    import numpy as np
except ImportError as e:
    print(f"envmap_mitsuba_lit: {e}: run tools/setup-mitsuba.sh", file=sys.stderr)
    sys.exit(2)

from envmap_mitsuba_check import write_env_maps  # noqa: E402 (after the import check)

W, H, YFOV, ALBEDO = 64, 64, 0.6, 0.8


def tray_render(args, env_map, out):
    scene = {"asset": {"version": "2.0"}, "extensionsUsed": ["TRAY_shape"], "scene": 0,
             "scenes": [{"nodes": [0, 1]}],
             "cameras": [{"type": "perspective",
                          "perspective": {"yfov": YFOV, "aspectRatio": W / H, "znear": 0.01}}],
             "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [ALBEDO] * 3 + [1],
                                                     "metallicFactor": 0,
                                                     "roughnessFactor": 1}}],
             "nodes": [{"camera": 0},
                       {"translation": [0, 0, -4],
                        "extensions": {"TRAY_shape": {"type": "sphere", "radius": 1,
                                                      "material": 0}}}]}
    gltf = out + ".gltf"
    with open(gltf, "w") as f:
        json.dump(scene, f)
    subprocess.run([os.path.join(args.build, "tray-render"), "-q", gltf, "--float",
                    "--integrator", "path", "--spp", str(args.spp), "--resolution", f"{W}x{H}",
                    "--env", env_map, "--env-rotate", str(args.rotate), "--no-default-light",
                    "-o", out], check=True)
    return np.array(mi.Bitmap(out))


def mitsuba_render(args, env_map):
    T = mi.ScalarTransform4f
    scene = mi.load_dict({
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 8},
        "sensor": {"type": "perspective", "fov_axis": "y", "fov": math.degrees(YFOV),
                   "to_world": T().look_at(origin=[0, 0, 0], target=[0, 0, -1], up=[0, 1, 0]),
                   "film": {"type": "hdrfilm", "width": W, "height": H,
                            "rfilter": {"type": "box"}, "pixel_format": "rgb"},
                   "sampler": {"type": "independent", "sample_count": args.spp}},
        "env": {"type": "envmap", "filename": env_map,
                "to_world": T().rotate([0, 1, 0], args.rotate)},
        "sphere": {"type": "sphere", "center": [0, 0, -4], "radius": 1,
                   "bsdf": {"type": "diffuse",
                            "reflectance": {"type": "rgb", "value": [ALBEDO] * 3}}},
    })
    return np.array(mi.render(scene))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--rotate", type=float, default=30.0)
    args = ap.parse_args()
    mi.set_variant("scalar_rgb")
    tmp = write_env_maps(args.build, "envlit_")
    worst = 0.0
    for name in ("windows.exr", "sky.exr"):
        env_map = os.path.join(tmp, name)
        tray = tray_render(args, env_map, os.path.join(tmp, "tray-" + name))
        mits = mitsuba_render(args, env_map)
        on = tray[:, :, 3] >= 1.0  # pixels fully on the sphere
        t, m = tray[on][:, :3].mean(axis=0), mits[on][:, :3].mean(axis=0)
        rel = np.abs(t - m) / m
        worst = max(worst, float(rel.max()))
        print(f"{name:12s} {int(on.sum())} sphere pixels, {args.spp} spp: TRay "
              f"{t[0]:.5f} {t[1]:.5f} {t[2]:.5f}  Mitsuba {m[0]:.5f} {m[1]:.5f} {m[2]:.5f}  "
              f"relative difference {rel[0]:.2%} {rel[1]:.2%} {rel[2]:.2%}")
    print(f"worst channel: {worst:.2%} (required: within 0.5%)")
    return 0 if worst <= 0.005 else 1


if __name__ == "__main__":
    sys.exit(main())
