#!/usr/bin/env python3
"""Farm figures for docs/farm.md, measured in one run:
  1. wall time of a 2-frame x 4-region job on the Slurm cluster of $SLURM_CONF (tray-farm submit
     until both frames are merged) against the same frames rendered by one tray-render process;
  2. tray-merge's peak memory (max RSS) for four 1920x1080 sample-range parts with every AOV
     that sample ranges allow, against the size of one part (decoded, float) and on disk.

Usage: bench/farm_bench.py BUILD_DIR [--spp 64] [--repeats 2]   (as root with a cluster up:
tools/slurm-local.sh start; eval "$(tools/slurm-local.sh env)")"""

import argparse
import os
import subprocess
import sys
import tempfile
import time

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ANIMATED = os.path.join(SOURCE, "..", "shared", "gltf-features", "BoxAnimated.glb")
WHITTED = os.path.join(SOURCE, "scenes", "whitted.gltf")
AOVS = "depth,normal,position,albedo,objectid,materialid,samples"


def farm_against_one_process(build, folder, spp):
    args = ["--integrator", "path", "--spp", str(spp), "--resolution", "320x240", "--fps", "2"]
    started = time.time()
    subprocess.run([os.path.join(build, "tray-farm"), "submit", ANIMATED, "--frames", "1-2",
                    "--split", "regions:4", "-o", os.path.join(folder, "farm.####.exr"),
                    "--job-dir", os.path.join(folder, "job")] + args, check=True,
                   capture_output=True)
    merged = [os.path.join(folder, "job", "state", "merged-%d" % f) for f in (0, 1)]
    while not all(os.path.exists(m) for m in merged):
        time.sleep(0.05)
    farm = time.time() - started
    started = time.time()
    subprocess.run([os.path.join(build, "tray-render"), ANIMATED, "--frames", "1-2", "-q", "-o",
                    os.path.join(folder, "one.####.exr")] + args, check=True, capture_output=True)
    return farm, time.time() - started


def merge_memory(build, folder):
    parts = []
    for k in range(4):
        part = os.path.join(folder, "s%d.exr" % k)
        subprocess.run([os.path.join(build, "tray-render"), WHITTED, "--spp", "4", "--resolution",
                        "1920x1080", "--aov", AOVS, "--sample-range", "%d,%d" % (k, k + 1), "-q",
                        "-o", part], check=True, capture_output=True)
        parts.append(part)
    merge = subprocess.Popen([os.path.join(build, "tray-merge")] + parts +
                             ["-o", os.path.join(folder, "merged.exr")])
    _, status, usage = os.wait4(merge.pid, 0)  # this child's own peak, not the renders'
    merge.returncode = os.waitstatus_to_exitcode(status)
    if merge.returncode != 0:
        sys.exit("tray-merge failed")
    peak_kb = usage.ru_maxrss
    info = subprocess.run(["oiiotool", "--info", "-v", parts[0]], capture_output=True, text=True)
    line = [x for x in info.stdout.splitlines() if "channel list" in x][0]
    channels = line.count(",") + 1
    decoded = 1920 * 1080 * channels * 4
    return peak_kb * 1024, decoded, os.path.getsize(parts[0]), channels


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("build")
    parser.add_argument("--spp", type=int, default=64)
    parser.add_argument("--repeats", type=int, default=2)
    args = parser.parse_args()
    build = os.path.abspath(args.build)
    with tempfile.TemporaryDirectory(prefix="farm-bench-") as folder:
        for r in range(args.repeats):
            run = os.path.join(folder, "run%d" % r)
            os.makedirs(run)
            farm, one = farm_against_one_process(build, run, args.spp)
            print("2 frames x 4 regions, 320x240, %d spp: farm %.1f s, one process %.1f s, "
                  "ratio %.2f" % (args.spp, farm, one, farm / one))
        peak, decoded, on_disk, channels = merge_memory(build, folder)
        print("tray-merge of 4 parts 1920x1080 x %d channels: peak RSS %.0f MB = %.2f decoded "
              "parts (%.0f MB each; %.0f MB on disk)" % (channels, peak / 2**20, peak / decoded,
                                                         decoded / 2**20, on_disk / 2**20))


if __name__ == "__main__":
    main()
