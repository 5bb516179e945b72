#!/usr/bin/python3
"""Chart 11 of docs/RESULTS.md from bench/gpu_modes.py's CSV.

    /usr/bin/python3 bench/gpu_modes_chart.py gpu_modes.csv gpu_modes.png

Left: error against the reference by bytes on the GPU (the tree export at
each cut-off, a line; the 4D store, a point; the CPU relighter's arrays in
RAM, a point at the same error). Middle: time per frame by bytes. Right:
per-pixel work by bytes (tree: transfer records read per sampled cell; 4D and CPU:
coefficients scattered per cell). Matplotlib's Agg backend.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    rows = list(csv.DictReader(open(sys.argv[1], newline="")))
    trees = [r for r in rows if r["mode"] == "gpu tree"]
    others = [r for r in rows if r["mode"] != "gpu tree"]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    panels = [("error", 100, "relative RMS error vs reference (%)"),
              ("ms", 1, "time per frame (ms)"), ("work", 1, "work per pixel")]
    style = {"gpu 4d": ("tab:red", "s"), "cpu relighter": ("tab:gray", "D")}
    for ax, (key, scale, label) in zip(axes, panels):
        pts = sorted((float(r["bytes"]) / 1e6, float(r[key]) * scale, r["cut_off"])
                     for r in trees if r[key])
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", color="tab:blue",
                    label="GPU tree (Boulton), by setting")
            for x, y, c in pts:
                ax.annotate(c, (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
        for r in others:
            if r[key]:
                color, marker = style[r["mode"]]
                ax.plot(float(r["bytes"]) / 1e6, float(r[key]) * scale, marker, color=color,
                        label=r["mode"] + (" (arrays in RAM)" if r["mode"] == "cpu relighter" else ""))
        ax.set_xlabel("bytes on the GPU (MB)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        if key == "ms":
            ax.set_yscale("log")
    axes[0].legend(fontsize=8)
    device = next((r["device"] for r in rows if r["mode"] == "gpu 4d"), "")
    fig.suptitle(f"Chart 11: relighting on the GPU, both modes and the CPU relighter ({device[:70]})",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
