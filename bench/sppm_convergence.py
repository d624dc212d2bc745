#!/usr/bin/env python3
"""SPPM's convergence (docs/sppm.md, "Measured"): the Cornell box against Mitsuba 3's converged
reference, and scenes/transport/caustic-spot.gltf against tools/caustic_power.py, at growing
iteration counts. Prints each render's time, channel-mean error, RMSE and relMSE (Cornell) or
caustic power error (tools/caustic_power.py's own line).

Usage: /usr/bin/python3 bench/sppm_convergence.py [BUILD_DIR] [--iterations 16,64,256]
       [--photons 200000] [--quick]   (--quick: 4,16 iterations, 64x64, 50000 photons)"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(os.path.dirname(ROOT), "shared", "reference")


def pixels(path):
    return oiio.ImageBuf(path).get_pixels(oiio.FLOAT)[..., :3].astype(np.float64)


def render(binary, scene, out, args):
    cmd = [binary, "--allow-any-path", "--integrator", "sppm", scene, "-o", out] + args
    run = subprocess.run(cmd, capture_output=True, text=True, check=True)
    seconds = re.search(r"([0-9.]+) s,", run.stdout + run.stderr)
    return float(seconds.group(1)) if seconds else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("build", nargs="?", default=os.path.join(ROOT, "build"))
    ap.add_argument("--iterations", default="16,64,256")
    ap.add_argument("--photons", type=int, default=200000)
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    binary = os.path.join(a.build, "tray-render")
    iterations = [4, 16] if a.quick else [int(k) for k in a.iterations.split(",")]
    photons = 50000 if a.quick else a.photons
    size = 64 if a.quick else 256
    ref = pixels(os.path.join(SHARED, "cornell-box.ref.exr"))
    with tempfile.TemporaryDirectory() as tmp:
        print(f"Cornell box {size}x{size}, {photons} photons per iteration, against Mitsuba 3")
        for k in iterations:
            out = os.path.join(tmp, f"cornell_{k}.exr")
            t = render(binary, os.path.join(SHARED, "cornell-box.gltf"), out,
                       ["--spp", str(k), "--photons", str(photons), "--resolution",
                        f"{size}x{size}"])
            img = pixels(out)
            err = img.reshape(-1, 3).mean(0) / ref.reshape(-1, 3).mean(0) - 1
            line = f"  {k:4d} iterations {t:8.1f} s  mean error " + " / ".join(
                f"{100 * e:+.3f}%" for e in err)
            if img.shape == ref.shape:
                rmse = np.sqrt(((img - ref) ** 2).mean())
                rel = ((img - ref) ** 2 / (ref ** 2 + 1e-2)).mean()
                line += f"  RMSE {rmse:.4f}  relMSE {rel:.5f}"
            print(line)
        print(f"caustic-spot 200x200, {photons} photons per iteration, --max-depth 5")
        outs = []
        for k in iterations:
            out = os.path.join(tmp, f"caustic_{k}.exr")
            t = render(binary, os.path.join(ROOT, "scenes", "transport", "caustic-spot.gltf"), out,
                       ["--spp", str(k), "--photons", str(photons), "--max-depth", "5",
                        "--resolution", "200x200"])
            print(f"  {k:4d} iterations {t:8.1f} s  {out}")
            outs.append(out)
        sys.stdout.flush()
        subprocess.run([sys.executable, os.path.join(ROOT, "tools", "caustic_power.py")] + outs,
                       check=True)


if __name__ == "__main__":
    main()
