#!/usr/bin/env python3
"""Uniform against noise-driven adaptive sampling at equal CPU time (issue 37), from the CSVs of
`tray-bench sweep --threads 1 --methods "path sobol,path sobol adaptive,path sobol adaptive
even,path sobol adaptive absolute,path sobol adaptive pixel,path sobol adaptive max,path sobol
adaptive neighbours"` (one per scene): the default rule (mse) and decision (wide: the RMS error of
the 5x5; before 2026-12-07's change, the 8 neighbours' mean), equal error (even), the default
rule on absolute error (--noise-metric absolute), with the pixel's own error deciding
(--noise-decision pixel), the neighbours' largest error (max) or their mean (neighbours) against
uniform (CSVs of before the change have "path sobol adaptive wide" instead). A method missing
from a CSV gives an empty table.

For each adaptive run (one --noise-threshold), the uniform error at the same CPU time is read off
the uniform runs' error-against-time line (piecewise linear in log-log, between the two uniform
runs around that time; runs of fewer than 16 spp, before the error settles into its rate, are left
out). The ratio uniform/adaptive > 1 means adaptive sampling has the lower error at equal time.
Both errors are against the same converged reference, whose own noise adds the same floor to
both and so pulls ratios towards 1 at the lowest errors.

Usage: bench/adaptive_report.py CSV... [--chart out.png]   (python3-matplotlib for --chart)
"""
import argparse
import csv
import os

from compare_report import loglog_crossing


def load(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in ("cpu_seconds", "rmse", "relmse", "relmse_trimmed", "spp", "rays", "bias"):
            r[k] = float(r[k])
    return rows


ADAPTIVE = (("path sobol adaptive", "mse"), ("path sobol adaptive even", "even"),
            ("path sobol adaptive absolute", "mse, --noise-metric absolute"),
            ("path sobol adaptive pixel", "mse, --noise-decision pixel (biased)"),
            ("path sobol adaptive max", "mse, --noise-decision max"),
            ("path sobol adaptive wide", "mse, --noise-decision wide (older CSVs)"),
            ("path sobol adaptive neighbours", "mse, --noise-decision neighbours"))


def compare(rows, metric, method, cost="cpu_seconds"):
    uniform = [(r[cost], r[metric]) for r in rows
               if r["method"] == "path sobol" and r["spp"] >= 16]
    out = []
    for r in rows:
        if r["method"] != method:
            continue
        u = loglog_crossing(uniform, r[cost])
        out.append((r["setting"], r[cost], r[metric], u, u / r[metric] if u else None,
                    r["bias"]))
    return out


def chart(tables, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    metrics = (("relmse_trimmed", "relMSE (0.1% worst pixels left out)"), ("rmse", "RMSE"))
    fig, axes = plt.subplots(len(metrics), len(tables), figsize=(5 * len(tables), 8.4),
                             squeeze=False)
    for row, (metric, ylabel) in enumerate(metrics):
        for ax, (scene, rows) in zip(axes[row], tables):
            for method, style, label in (
                    ("path sobol", "o-", "uniform (spp 1..1024)"),
                    ("path sobol adaptive", "s-",
                     "adaptive, mse rule, default decision (threshold 0.1..0.01)"),
                    ("path sobol adaptive even", "^--", "adaptive, even rule (0.1..0.01)"),
                    ("path sobol adaptive absolute", "d-.",
                     "adaptive, mse, absolute error (0.02..0.003)"),
                    ("path sobol adaptive pixel", "x:",
                     "adaptive, mse, pixel decides (biased; 0.1..0.01)"),
                    ("path sobol adaptive max", "v-",
                     "adaptive, mse, neighbours' max decides (0.1..0.01)"),
                    ("path sobol adaptive wide", "*-",
                     "adaptive, mse, 5x5 RMS decides (0.1..0.01)"),
                    ("path sobol adaptive neighbours", "+-",
                     "adaptive, mse, 8 neighbours' mean decides (0.1..0.01)")):
                rs = sorted((r for r in rows if r["method"] == method),
                            key=lambda r: r["cpu_seconds"])
                ax.plot([r["cpu_seconds"] for r in rs], [r[metric] for r in rs], style,
                        label=label)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_title(scene)
            ax.set_xlabel("CPU seconds (1 thread)")
            ax.set_ylabel(ylabel)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv", nargs="+")
    ap.add_argument("--chart", help="write the relMSE-against-time chart here")
    ap.add_argument("--cost", choices=("cpu_seconds", "rays"), default="cpu_seconds",
                    help="equal cost in CPU seconds (default) or in rays traced (the work, "
                    "without the passes' overhead; steady when other jobs share the host)")
    a = ap.parse_args()
    tables = []
    for path in a.csv:
        rows = load(path)
        scene = rows[0]["scene"] if rows else os.path.basename(path)
        tables.append((scene, rows))
        for metric in ("relmse_trimmed", "relmse", "rmse"):
            for method, rule in ADAPTIVE:
                print(f"\n{scene}, {metric}, rule {rule}: adaptive against uniform at equal "
                      f"{a.cost}\n")
                print(f"| threshold | {a.cost} | adaptive | uniform at that cost | uniform / "
                      "adaptive | mean bias |")
                print("|---|---|---|---|---|---|")
                for setting, t, e, u, ratio, bias in compare(rows, metric, method, a.cost):
                    us = f"{u:.3e}" if u else "outside the uniform runs"
                    rs = f"{ratio:.2f}" if ratio else "-"
                    print(f"| {setting.split('=')[1]} | {t:.3g} | {e:.3e} | {us} | {rs} "
                          f"| {bias:+.2e} |")
    if a.chart:
        chart(tables, a.chart)
        print(f"\nwrote {a.chart}")


if __name__ == "__main__":
    main()
