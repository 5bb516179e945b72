#!/usr/bin/python3
"""Plots the near-field CSVs of bench_charts_near (docs/RESULTS.md charts 9, 10
and the grazing-loss chart).

    /usr/bin/python3 bench/charts_near.py CSV_DIR PNG_DIR
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def chart9(r, out):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, sweep, xlabel in ((axes[0], "height", "light height above the floor (size 1.4 x 1.0)"),
                              (axes[1], "size", "light size factor (x 1.4 x 1.0, height 1.2)")):
        pts = [x for x in r if x["sweep"] == sweep]
        xs = [float(p[sweep]) for p in pts]
        ax.plot(xs, [float(p["near_rel_rms"]) for p in pts], "o-", color="tab:green",
                label="near field (affine wavelet, 1 % / 30 %)")
        ax.plot(xs, [float(p["distant_rel_rms"]) for p in pts], "s--", color="tab:red",
                label="same light treated as distant")
        ax.plot(xs, [float(p["near_facing_rel_rms"]) for p in pts], "o:", color="tab:green",
                alpha=0.6, label="near field, receivers facing the light plane")
        ax.plot(xs, [float(p["distant_facing_rel_rms"]) for p in pts], "s:", color="tab:red",
                alpha=0.6, label="distant, receivers facing the light plane")
        ax.plot(xs, [float(p["grazing_loss_s4"]) for p in pts], "-", color="tab:gray",
                label="energy outside the plane:4 face (reference)")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("relative RMS error vs Monte-Carlo reference")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("Chart 9: cubes-wall, plane:4, N = 32 — near field against distant")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


FLOOR = 1e-5


def chart10(r, out):
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    styles = {"softbox": "tab:blue", "checker8": "tab:orange"}
    for col, sweep in enumerate(("source", "target")):
        fixed_key = "target_fraction" if sweep == "source" else "source_fraction"
        var_key = "source_fraction" if sweep == "source" else "target_fraction"
        for tex, color in styles.items():
            for fixed, style in (("1", "-"), ("0.3", "--"), ("0.01", "--")):
                pts = [x for x in r if x["texture"] == tex and x["sweep"] == sweep and
                       abs(float(x[fixed_key]) - float(fixed)) < 1e-9]
                if not pts:
                    continue
                xs = [100 * float(p[var_key]) for p in pts]
                label = f"{tex}, {fixed_key.split('_')[0]} {100 * float(fixed):g} %"
                # Exact zeros (nothing truncated) drawn at the floor.
                axes[0][col].plot(xs, [max(FLOOR, float(p["rel_rms_reference"])) for p in pts],
                                  style, color=color, marker="o", ms=3,
                                  label=label + " vs reference")
                axes[0][col].plot(xs, [max(FLOOR, float(p["rel_rms_untruncated"])) for p in pts],
                                  style, color=color, marker="x", ms=4, alpha=0.5,
                                  label=label + " vs untruncated")
                axes[1][col].plot(xs, [float(p["ms_per_frame"]) for p in pts], style,
                                  color=color, marker="o", ms=3, label=label)
        for row in (0, 1):
            axes[row][col].set_xscale("log")
            axes[row][col].set_xlabel(f"{sweep}-level terms kept (%)")
            axes[row][col].grid(True, which="both", alpha=0.3)
        axes[0][col].set_yscale("log")
        axes[0][col].set_ylim(bottom=FLOOR / 2)
        axes[0][col].set_ylabel("relative RMS error")
        axes[1][col].set_ylabel("ms per frame (64x64 samples, one core)")
        axes[0][col].legend(fontsize=6)
        axes[1][col].legend(fontsize=6)
    fig.suptitle("Chart 10: error and time against source- and target-level truncation "
                 "(paper Figs. 10, 11)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def grazing(r, out):
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for h in sorted({x["height"] for x in r if x["curve"] == "loss"}, key=float):
        pts = [x for x in r if x["curve"] == "loss" and x["height"] == h]
        ax.plot([float(p["face_size"]) for p in pts], [float(p["value"]) for p in pts], "o-",
                label=f"measured: light at height {float(h):g} (cubes-wall)")
    for curve, style in (("hemisphere_coverage", "k-"), ("cosine_lobe_coverage", "k--")):
        pts = [x for x in r if x["curve"] == curve]
        ax.plot([float(p["face_size"]) for p in pts], [1 - float(p["value"]) for p in pts], style,
                label="1 − " + curve.replace("_", " ") + " (Fig. 7e)")
    ax.set_yscale("log")
    ax.set_xlabel("expanded face size S")
    ax.set_ylabel("fraction of energy / solid angle missed")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title("Grazing-angle loss of the expanded face (§5.4.3)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    src, dst = sys.argv[1], sys.argv[2]
    os.makedirs(dst, exist_ok=True)
    for name, fn in (("near_height", chart9), ("near_terms", chart10),
                     ("near_grazing", grazing)):
        path = os.path.join(src, name + ".csv")
        if not os.path.exists(path):
            print(f"charts_near: {path} missing, skipped")
            continue
        fn(rows(path), os.path.join(dst, name + ".png"))
        print(f"charts_near: {os.path.join(dst, name + '.png')}")


if __name__ == "__main__":
    main()
