#!/usr/bin/env python3
"""TRay's random-walk subsurface scattering (docs/subsurface.md) against Mitsuba 3's `volpathmis`.

One scene, written here for both renderers: a glass sphere (radius 1, IOR 1.5, smooth) filled
with a homogeneous medium (sigma_t per channel, single-scattering albedo, Henyey-Greenstein g),
lit by a square area light above it (one-sided, facing down, radiance 5, black surface) and a
constant environment of radiance 0.5, seen from (0, 0, 4) looking down -z (yfov 0.7 rad),
box pixel filter. TRay reads it as glTF: TRAY_shape sphere, KHR_materials_transmission + ior
+ volume (sigma_a = (1 - albedo) sigma_t as attenuationColor exp(-sigma_a) at distance 1) +
TRAY_materials_scattering (sigma_s = albedo sigma_t, g). Mitsuba gets the same as a dict:
`sphere` with a `dielectric` BSDF and a `homogeneous` interior (sigma_t, albedo, `hg` phase),
`rectangle` with an `area` emitter, `constant` emitter, rendered by `volpathmis` (spectral MIS;
`--integrator volpath` for the plain one, whose weights in chromatic media are heavy-tailed).

Both are unbiased with unlimited depth (TRay: --max-depth 1000 surface segments, medium events
not counted, docs/subsurface.md; Mitsuba: max_depth -1), so converged channel means must agree.
Printed (a markdown table): channel means over the whole image and over the pixels that see
the sphere's interior (a disk of 0.9 x its angular radius), each the mean of --runs renders
(seeds 1..runs) ± the standard error from their spread, and the relative differences.

Usage (Mitsuba from tools/setup-mitsuba.sh):
  DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 \\
    build/mitsuba-venv/bin/python bench/subsurface_mitsuba.py --tray-build build --spp 512 --runs 4
"""
import argparse
import base64
import json
import math
import os
import struct
import subprocess
import sys
import tempfile
import time

import mitsuba as mi
import numpy as np

YFOV, CAM_Z, LIGHT_Y, LIGHT_RADIANCE, ENV = 0.7, 4.0, 3.0, 5.0, 0.5

SCENES = {
    # name: (sigma_t, albedo, g)
    "low-albedo": ([2.0, 3.0, 4.0], [0.3, 0.3, 0.3], 0.0),
    "high-albedo": ([4.0, 6.0, 10.0], [0.99, 0.97, 0.95], 0.3),
}


def tray_gltf(sigma_t, albedo, g):
    sigma_a = [(1 - a) * s for s, a in zip(sigma_t, albedo)]
    sigma_s = [a * s for s, a in zip(sigma_t, albedo)]
    pos = [(-1, LIGHT_Y, -1), (1, LIGHT_Y, -1), (1, LIGHT_Y, 1), (-1, LIGHT_Y, 1)]
    data = b"".join(struct.pack("<3f", *p) for p in pos) + struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    return {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["TRAY_shape", "TRAY_environment", "TRAY_materials_scattering",
                           "KHR_materials_transmission", "KHR_materials_ior",
                           "KHR_materials_volume", "KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2],
                    "extensions": {"TRAY_environment": {"background": [ENV] * 3}}}],
        "nodes": [
            {"camera": 0, "translation": [0, 0, CAM_Z]},
            {"name": "medium", "extensions": {"TRAY_shape": {"type": "sphere", "radius": 1,
                                                             "material": 0}}},
            {"name": "light", "mesh": 0},
        ],
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": YFOV, "aspectRatio": 1, "znear": 0.01}}],
        "materials": [
            {"name": "medium",
             "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0,
                                      "roughnessFactor": 0},
             "extensions": {
                 "KHR_materials_transmission": {"transmissionFactor": 1},
                 "KHR_materials_ior": {"ior": 1.5},
                 "KHR_materials_volume": {
                     "attenuationColor": [math.exp(-s) for s in sigma_a],
                     "attenuationDistance": 1},
                 "TRAY_materials_scattering": {"scatteringCoefficient": sigma_s,
                                               "anisotropy": g}}},
            {"name": "light",
             "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0},
             "emissiveFactor": [1, 1, 1],
             "extensions": {"KHR_materials_emissive_strength":
                            {"emissiveStrength": LIGHT_RADIANCE}}},
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
                                    "material": 1}]}],
        "buffers": [{"byteLength": len(data), "uri": uri}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-1, LIGHT_Y, -1], "max": [1, LIGHT_Y, 1]},
            {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
    }


def mitsuba_scene(sigma_t, albedo, g, size, spp, integrator):
    T = mi.ScalarTransform4f
    rgb = lambda v: {"type": "rgb", "value": v}  # noqa: E731
    return {
        "type": "scene",
        "integrator": {"type": integrator, "max_depth": -1},
        "sensor": {"type": "perspective", "fov_axis": "y", "fov": math.degrees(YFOV),
                   "to_world": T().look_at(origin=[0, 0, CAM_Z], target=[0, 0, 0], up=[0, 1, 0]),
                   "film": {"type": "hdrfilm", "width": size, "height": size,
                            "rfilter": {"type": "box"}, "pixel_format": "rgb"},
                   "sampler": {"type": "independent", "sample_count": spp}},
        "env": {"type": "constant", "radiance": rgb([ENV] * 3)},
        "light": {"type": "rectangle",
                  "to_world": T().translate([0, LIGHT_Y, 0]) @ T().rotate([1, 0, 0], 90),
                  "emitter": {"type": "area", "radiance": rgb([LIGHT_RADIANCE] * 3)},
                  "bsdf": {"type": "diffuse", "reflectance": rgb([0, 0, 0])}},
        "sphere": {"type": "sphere", "radius": 1.0,
                   "bsdf": {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0},
                   # sigma_t as an RGB in [0, 1] times `scale` (Mitsuba reads the RGB as a
                   # reflectance-like spectrum, bounded by 1).
                   "interior": {"type": "homogeneous",
                                "sigma_t": rgb([s / max(sigma_t) for s in sigma_t]),
                                "scale": max(sigma_t), "albedo": rgb(albedo),
                                "phase": {"type": "hg", "g": g}}},
    }


def interior_mask(size):
    """Pixels whose centre ray meets the sphere well inside its silhouette."""
    t = math.tan(YFOV / 2)
    c = (np.arange(size) + 0.5) / size * 2 - 1
    x, y = np.meshgrid(c * t, c * t)
    return np.arctan(np.hypot(x, y)) < 0.9 * math.asin(1 / CAM_Z)


def read_exr(path):
    return np.array(mi.Bitmap(path), dtype=np.float64)[:, :, :3]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--tray-build", default="build")
    p.add_argument("--size", type=int, default=128)
    p.add_argument("--spp", type=int, default=1024)
    p.add_argument("--variant", default="llvm_ad_rgb")
    p.add_argument("--out", default=None, help="folder to keep the renders (EXR) in")
    p.add_argument("--scenes", nargs="*", default=list(SCENES))
    p.add_argument("--runs", type=int, default=4,
                   help="independent renders (seeds 1..runs) per renderer: the standard error")
    p.add_argument("--integrator", default="volpathmis",
                   help="Mitsuba's: volpathmis (spectral MIS, as TRay) or volpath (one "
                        "channel's pdf: unbiased but heavy-tailed in chromatic media)")
    a = p.parse_args()
    mi.set_variant(a.variant)
    out = a.out or tempfile.mkdtemp(prefix="tray-sss-")
    os.makedirs(out, exist_ok=True)
    mask = interior_mask(a.size)
    print(f"{a.size}x{a.size}, {a.spp} spp x {a.runs} runs; channel means ± standard error: "
          f"whole image | sphere interior ({mask.sum()} px)")
    print("| scene | renderer | time s | R | G | B | interior R | interior G | interior B |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name in a.scenes:
        sigma_t, albedo, g = SCENES[name]
        gltf = os.path.join(out, f"{name}.gltf")
        with open(gltf, "w") as f:
            json.dump(tray_gltf(sigma_t, albedo, g), f, indent=1)
        scene = mi.load_dict(mitsuba_scene(sigma_t, albedo, g, a.size, a.spp, a.integrator))
        runs = {"TRay path": [], f"Mitsuba {a.integrator}": []}
        times = {k: 0.0 for k in runs}
        for run in range(a.runs):
            exr = os.path.join(out, f"{name}.tray.{run}.exr")
            t0 = time.time()
            subprocess.run([os.path.join(a.tray_build, "tray-render"), "--allow-any-path",
                            "--integrator", "path", "--max-depth", "1000", "--spp", str(a.spp),
                            "--seed", str(run + 1), "--resolution", f"{a.size}x{a.size}",
                            "--float", gltf, "-o", exr], check=True, capture_output=True)
            times["TRay path"] += time.time() - t0
            runs["TRay path"].append(read_exr(exr))
            t0 = time.time()
            img = np.array(mi.render(scene, seed=run + 1))[:, :, :3].astype(np.float64)
            times[f"Mitsuba {a.integrator}"] += time.time() - t0
            mi.Bitmap(img.astype(np.float32)).write(os.path.join(out, f"{name}.mitsuba.{run}.exr"))
            runs[f"Mitsuba {a.integrator}"].append(img)
        stats = {}
        for who, ims in runs.items():
            whole = np.array([im.reshape(-1, 3).mean(0) for im in ims])
            inner = np.array([im[mask].mean(0) for im in ims])
            # Mean over the runs and its standard error from their spread.
            se = lambda v: v.std(0, ddof=1) / math.sqrt(len(v)) if len(v) > 1 else 0 * v[0]  # noqa
            stats[who] = (whole.mean(0), se(whole), inner.mean(0), se(inner))
            w, ws, i, is_ = stats[who]
            print(f"| {name} | {who} | {times[who]:.0f} | " +
                  " | ".join(f"{v:.5f} ± {e:.5f}" for v, e in zip(w, ws)) + " | " +
                  " | ".join(f"{v:.5f} ± {e:.5f}" for v, e in zip(i, is_)) + " |")
        (tw, tws, ti, tis), (mw, mws, mi_, mis) = stats.values()
        rel = lambda x, y, ex, ey: f"{100 * (x / y - 1):+.2f}% ± {100 * math.hypot(ex, ey) / y:.2f}%"  # noqa
        print(f"| {name} | TRay / Mitsuba - 1 | | " +
              " | ".join(rel(*v) for v in zip(tw, mw, tws, mws)) + " | " +
              " | ".join(rel(*v) for v in zip(ti, mi_, tis, mis)) + " |")
        sys.stdout.flush()
    print(f"renders in {out}")


if __name__ == "__main__":
    main()
