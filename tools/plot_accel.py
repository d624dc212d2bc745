#!/usr/bin/env python3
"""Charts bench/accel_bench.cpp's CSV: ray throughput against triangle count (log axes), one
panel per ray kind (camera, shadow, diffuse bounce), one line per accelerator, plus build time.
Usage: tools/plot_accel.py accel_bench.csv [--out docs/accelerators.png]  (python3-matplotlib)"""
import argparse, csv
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

STYLE = {"embree": "k-o", "bvh": "b-s", "bvh-nocache": "c--", "bvh-gs": "g-^", "naive": "r-x"}
LABEL = {"embree": "Embree", "bvh": "bvh (binned SAH, 4-wide)",
         "bvh-nocache": "bvh without last-occluder cache",
         "bvh-gs": "bvh-gs (Goldsmith-Salmon)", "naive": "naive"}


def load(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in r:
            if k not in ("scene", "accel"):
                r[k] = float(r[k])
    return rows


def print_table(rows):
    """Embree vs bvh per scene: build times and each ray kind's bvh time over Embree's time."""
    get = {(r["scene"], r["accel"]): r for r in rows}
    print("| scene | triangles | build ms embree / bvh | bvh time / embree time: camera | shadow"
          " | bounce |")
    print("|---|---:|---:|---:|---:|---:|")
    for r in rows:
        if r["accel"] != "embree" or (r["scene"], "bvh") not in get:
            continue
        b = get[(r["scene"], "bvh")]
        ratio = lambda k: r[k] / b[k]  # throughput ratio = time ratio inverted
        print(f"| {r['scene']} | {int(r['triangles'])} | {r['build_ms']:.0f} / {b['build_ms']:.0f}"
              f" | {ratio('camera_mrays'):.2f} | {ratio('shadow_mrays'):.2f}"
              f" | {ratio('bounce_mrays'):.2f} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("--out", default="docs/accelerators.png")
    ap.add_argument("--table", action="store_true",
                    help="print a Markdown table of Embree's time over bvh's per scene, no chart")
    args = ap.parse_args()
    rows = load(args.csv)
    if args.table:
        print_table(rows)
        return
    by_accel = defaultdict(list)
    for r in rows:
        by_accel[r["accel"]].append(r)
    panels = [("camera_mrays", "camera rays, Mrays/s"), ("shadow_mrays", "shadow rays, Mrays/s"),
              ("bounce_mrays", "diffuse bounce rays, Mrays/s"), ("build_ms", "build time, ms")]
    fig, axes = plt.subplots(1, 4, figsize=(18, 4.5))
    for ax, (key, title) in zip(axes, panels):
        for accel, rs in by_accel.items():
            if accel == "bvh-nocache" and key != "shadow_mrays":
                continue  # the same tree as bvh: only its shadow rays differ
            rs = sorted((r for r in rs if r[key] > 0), key=lambda r: r["triangles"])
            if not rs:
                continue
            ax.plot([r["triangles"] for r in rs], [r[key] for r in rs],
                    STYLE.get(accel, "-"), label=LABEL.get(accel, accel), alpha=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("triangles")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[1].legend(fontsize=8)
    fig.suptitle("TRay accelerators on the same scenes and rays (bench/accel_bench.cpp)")
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
