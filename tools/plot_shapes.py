#!/usr/bin/env python3
"""Charts `build/shape_bench --images SPP --csv FILE`: each analytic shape against its
tessellations, image RMSE (against a converged render of the analytic shape) over memory and
over render time (issue 41, docs/shapes.md).

  tools/plot_shapes.py shapes.csv docs/images/shapes-analytic-vs-mesh.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rows = list(csv.DictReader(open(sys.argv[1]), delimiter="\t"))
    shapes = []
    for r in rows:
        if r["shape"] not in shapes:
            shapes.append(r["shape"])
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.8))
    for i, shape in enumerate(shapes):
        colour = "C%d" % i
        label = shape.split(" (")[0]
        own = [r for r in rows if r["shape"] == shape and float(r["rmse"]) >= 0]
        meshes = [r for r in own if r["model"].startswith("mesh")]
        analytic = [r for r in own if r["model"] == "analytic"]
        for ax, key, scale in ((axes[0], "bytes", 1 / 1024), (axes[1], "render_s", 1)):
            ax.plot([float(r[key]) * scale for r in meshes], [float(r["rmse"]) for r in meshes],
                    "o-", color=colour, label=label + " mesh (1e-2, 1e-3, 1e-4)")
            ax.plot([float(r[key]) * scale for r in analytic],
                    [float(r["rmse"]) for r in analytic], "*", color=colour, markersize=14,
                    label=label + " analytic")
    axes[0].set_xscale("log")
    axes[0].set_xlabel("geometry + accelerator memory (KiB, log)")
    axes[1].set_xlabel("render CPU seconds (path, one thread)")
    for ax in axes:
        ax.set_ylabel("image RMSE against the converged analytic render")
        ax.grid(True, alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=7, ncol=5, loc="lower center")
    fig.suptitle("Analytic shapes against their tessellations: the analytic star is the noise floor")
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    fig.savefig(sys.argv[2], dpi=100)


if __name__ == "__main__":
    main()
