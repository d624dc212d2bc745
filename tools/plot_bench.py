#!/usr/bin/env python3
"""Charts a tray-bench sweep: RMSE (and relMSE) against wall time on log-log axes, one line per
method, and a markdown report with the Pareto front (the cheapest method for each error level).
relMSE divides each pixel's squared error by its reference value squared (+1e-2), so that a few
very bright pixels (a visible light's edge) do not outweigh the rest of the image.
Usage: tools/plot_bench.py SWEEP.csv [--out-dir DIR]   (needs python3-matplotlib)"""
import argparse, csv, os, sys
from collections import defaultdict

def load(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in ("seconds", "rays", "rmse", "relmse", "bias", "max_abs"):
            r[k] = float(r[k])
    return rows

def pareto(rows):
    """Runs no other run beats on both time and RMSE, sorted by time."""
    front, best = [], float("inf")
    for r in sorted(rows, key=lambda r: (r["seconds"], r["rmse"])):
        if r["rmse"] < best:
            front.append(r)
            best = r["rmse"]
    return front

def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("--out-dir", default=None)
    a = ap.parse_args()
    rows = load(a.csv)
    if not rows:
        sys.exit(f"plot_bench: {a.csv}: no rows")
    out = a.out_dir or os.path.dirname(os.path.abspath(a.csv))
    stem = os.path.splitext(os.path.basename(a.csv))[0]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    by_method = defaultdict(list)
    for r in rows:
        by_method[r["method"]].append(r)
    # Colour by method, line style by accelerator, marker by thread count, so that the variants
    # tray-bench adds as " [embree]", " [2t]" stay readable.
    bases = sorted({m.split(" [")[0] for m in by_method})
    accels = sorted({r["accel"] for r in rows})
    threads = sorted({r["threads"] for r in rows})
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    styles, markers = ["-", "--", ":", "-."], ["o", "s", "^", "D"]
    def chart(metric, label, suffix):
        fig, ax = plt.subplots(figsize=(9, 5.5))
        for method, rs in sorted(by_method.items()):
            rs.sort(key=lambda r: r["rays"])  # cost order; wall time is noisy at equal cost
            r0 = rs[0]
            ax.plot([r["seconds"] for r in rs], [max(r[metric], 1e-9) for r in rs],
                    color=colours[bases.index(method.split(" [")[0]) % len(colours)],
                    ls=styles[accels.index(r0["accel"]) % len(styles)],
                    marker=markers[threads.index(r0["threads"]) % len(markers)], ms=4,
                    label=method)
        if metric == "rmse":
            ax.plot([r["seconds"] for r in front], [max(r["rmse"], 1e-6) for r in front], "k-",
                    lw=2.5, alpha=0.25, label="Pareto front")
        ax.set_xscale("log"); ax.set_yscale("log")
        ax.set_xlabel("wall time (s)"); ax.set_ylabel(f"{label} against reference")
        ax.set_title(f"{stem}: {label} against time")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        fig.tight_layout()
        path = os.path.join(out, f"{stem}-{suffix}-vs-time.png")
        fig.savefig(path, dpi=110)
        return path

    front = pareto(rows)
    png = chart("rmse", "RMSE", "error")
    # The relMSE chart only where it tells something the RMSE one does not: denoised lines.
    rel_png = chart("relmse", "relMSE", "relmse") if any("OIDN" in m for m in by_method) else None

    md = os.path.join(out, f"{stem}-report.md")
    with open(md, "w") as f:
        f.write(f"# {stem}: speed against accuracy\n\n![error vs time]({os.path.basename(png)})\n\n")
        if rel_png:
            f.write(f"![relMSE vs time]({os.path.basename(rel_png)})\n\n")
        f.write("Wall time and rays per render; RMSE, relMSE and bias against the reference (each "
                "integrator's own converged render unless tray-bench was given --reference). "
                "Regenerate with tools/make_bench_charts.sh.\n\n")
        f.write("## Pareto front: the cheapest method for each error level\n\n")
        f.write("| RMSE below | cheapest method | setting | seconds | Mrays |\n|---|---|---|---|---|\n")
        for r in front:
            f.write(f"| {r['rmse']:.3e} | {r['method']} | {r['setting']} | {r['seconds']:.3f} | {r['rays']*1e-6:.2f} |\n")
        f.write("\n## All runs\n\n| method | setting | seconds | Mrays | RMSE | relMSE | bias |\n|---|---|---|---|---|---|---|\n")
        for r in sorted(rows, key=lambda r: (r["method"], r["seconds"])):
            f.write(f"| {r['method']} | {r['setting']} | {r['seconds']:.3f} | {r['rays']*1e-6:.2f} | "
                    f"{r['rmse']:.3e} | {r['relmse']:.3e} | {r['bias']:+.2e} |\n")
    print(f"wrote {png} and {md}")

if __name__ == "__main__":
    main()
