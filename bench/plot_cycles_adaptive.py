#!/usr/bin/env python3
"""Charts bench/cycles_adaptive.py's report: relMSE against seconds (1 thread, set-up excluded)
for TRay's and Cycles' adaptive sampling, one panel per asset, each renderer against its own
reference. Usage: bench/plot_cycles_adaptive.py REPORT.txt --out chart.png (python3-matplotlib)."""
import argparse
import re
from collections import defaultdict

LINE = re.compile(r"^\s+(\S+)\s+(tray|cycles)\s+threshold (\S+)\s+([0-9.]+) s\s+RMSE ([0-9.]+)"
                  r"\s+relMSE ([0-9.e+-]+)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("report")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    runs = defaultdict(list)  # (asset, renderer) -> [(seconds, relMSE)]
    with open(a.report) as f:
        for line in f:
            m = LINE.match(line)
            if m:
                runs[(m.group(1), m.group(2))].append((float(m.group(4)), float(m.group(6))))
    assets = sorted({asset for asset, _ in runs})
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(assets), figsize=(5 * len(assets), 4), squeeze=False)
    for ax, asset in zip(axes[0], assets):
        for renderer, style, label in (("tray", "s-", "TRay, --noise-threshold"),
                                       ("cycles", "o--", "Cycles 5.2, adaptive_threshold")):
            pts = sorted(runs[(asset, renderer)])
            ax.plot([p[0] for p in pts], [p[1] for p in pts], style, label=label)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(asset)
        ax.set_xlabel("seconds, 1 thread (set-up excluded)")
        ax.set_ylabel("relMSE against its own reference")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
