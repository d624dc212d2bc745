#!/usr/bin/env python3
"""TRay's environment map orientation and lookup against Mitsuba 3's `envmap`, direction by
direction.

TRay renders a scene with nothing in view but the map (one ray through each pixel centre:
--pixel-sampler center, box filter), so each pixel is TRay's Le along that pixel's ray.
Mitsuba's envmap plugin, loaded on the same file with to_world = rotate([0, 1, 0], angle),
is evaluated along the same directions. Both are bilinear lookups of the same texels, so they
must agree to float precision wherever the map is smooth; the figures are printed per view
(forward, right, straight up at the pole).

Usage (Mitsuba in the venv of tools/setup-mitsuba.sh; only its scalar_rgb variant is used):
  build/mitsuba-venv/bin/python bench/envmap_mitsuba_check.py [--build build] [--rotate 30]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

try:
    import mitsuba as mi
    import numpy as np
except ImportError as e:
    print(f"envmap_mitsuba_check: {e}: run tools/setup-mitsuba.sh", file=sys.stderr)
    sys.exit(2)

W, H, YFOV = 96, 48, 1.6

# Camera node rotations (glTF quaternions x, y, z, w) for three views; cameras look down -Z.
VIEWS = {
    "forward (-Z)": [0.0, 0.0, 0.0, 1.0],
    "right (+X)": [0.0, -math.sin(math.pi / 4), 0.0, math.cos(math.pi / 4)],
    "up (+Y pole)": [math.sin(math.pi / 4), 0.0, 0.0, math.cos(math.pi / 4)],
}


def rotate(q, v):
    """Rotates v by the unit quaternion q = (x, y, z, w)."""
    x, y, z, w = q
    u = np.array([x, y, z])
    return 2 * np.dot(u, v) * u + (w * w - np.dot(u, u)) * v + 2 * w * np.cross(u, v)


def pixel_directions(q):
    """World directions of TRay's camera rays through the pixel centres (glTF perspective)."""
    t = math.tan(YFOV / 2)
    aspect = W / H
    dirs = np.zeros((H, W, 3))
    for y in range(H):
        for x in range(W):
            d = np.array([(2 * (x + 0.5) / W - 1) * t * aspect, (1 - 2 * (y + 0.5) / H) * t, -1.0])
            d = rotate(q, d / np.linalg.norm(d))
            dirs[y, x] = d
    return dirs


def write_env_maps(build, prefix):
    """env_bench's maps (windows.exr, sky.exr) written into a new temporary folder, returned."""
    tmp = tempfile.mkdtemp(prefix=prefix)
    subprocess.run([os.path.join(build, "env_bench"), "--write-maps", tmp], check=True,
                   stdout=subprocess.DEVNULL)
    return tmp


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--rotate", type=float, default=30.0)
    args = ap.parse_args()
    mi.set_variant("scalar_rgb")
    tmp = write_env_maps(args.build, "envcheck_")
    # The windows map is flat but for its sharp window edges; the sun sky has a gradient
    # everywhere and a 2-degree sun. Both are checked.
    for name in ("windows.exr", "sky.exr"):
        env_map = os.path.join(tmp, name)
        emitter = mi.load_dict({"type": "envmap", "filename": env_map,
                                "to_world": mi.ScalarTransform4f().rotate([0, 1, 0], args.rotate)})
        for view, q in VIEWS.items():
            scene = {"asset": {"version": "2.0"}, "extensionsUsed": ["TRAY_shape"], "scene": 0,
                     "scenes": [{"nodes": [0, 1]}],
                     "cameras": [{"type": "perspective", "perspective":
                                  {"yfov": YFOV, "aspectRatio": W / H, "znear": 0.01}}],
                     "nodes": [{"camera": 0, "rotation": q},
                               {"translation": [0, -1000 if view.startswith("up") else 1000, 0],
                                "extensions": {"TRAY_shape": {"type": "sphere", "radius": 1}}}]}
            gltf = os.path.join(tmp, "view.gltf")
            with open(gltf, "w") as f:
                json.dump(scene, f)
            out = os.path.join(tmp, "view.exr")
            subprocess.run([os.path.join(args.build, "tray-render"), "-q", gltf, "--float",
                            "--resolution", f"{W}x{H}", "--pixel-sampler", "center",
                            "--filter", "box", "--env", env_map, "--env-rotate", str(args.rotate),
                            "-o", out], check=True)
            tray = np.array(mi.Bitmap(out))[:, :, :3]
            dirs = pixel_directions(q)
            mits = np.zeros_like(tray)
            si = mi.SurfaceInteraction3f()
            for y in range(H):
                for x in range(W):
                    si.wi = mi.Vector3f(*(-dirs[y, x]))
                    mits[y, x] = np.array(emitter.eval(si))
            rel = np.abs(tray - mits) / (np.abs(mits) + 1e-3)
            print(f"{name:12s} {view:14s} mean TRay {tray.mean():.5f} Mitsuba {mits.mean():.5f}; "
                  f"median rel. diff {np.median(rel):.2e}, 99th pct {np.percentile(rel, 99):.2e}, "
                  f"pixels within 1e-3: {100 * np.mean(rel < 1e-3):.1f}%")


if __name__ == "__main__":
    main()
