#!/usr/bin/python3
"""Chart 12 of docs/RESULTS.md from bench_charts_bounces' CSVs.

    /usr/bin/python3 bench/charts_bounces.py CSV_DIR PNG_DIR

Three panels per case: the relighting's error against the path-traced
reference vs B, the bake's CPU time vs B (the ratio to B = 0 marked), and
the energy of each bounce, rms_ratio[b] = sqrt(E_b / E_0), of the B = 4 store.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: charts_bounces.py CSV_DIR PNG_DIR")
    csv_dir, png_dir = sys.argv[1], sys.argv[2]
    path = os.path.join(csv_dir, "bounces.csv")
    if not os.path.exists(path):
        print(f"charts_bounces.py: {path} missing, chart skipped")
        return
    rows = read_rows(path)
    energy = read_rows(os.path.join(csv_dir, "bounce_energy.csv"))
    cases = []
    for r in rows:
        if r["case"] not in cases:
            cases.append(r["case"])
    fig, (ex, tx, gx) = plt.subplots(1, 3, figsize=(18, 4.8))
    for case in cases:
        rs = [r for r in rows if r["case"] == case]
        b = [int(r["bounces"]) for r in rs]
        ex.plot(b, [100 * float(r["rel_rms"]) for r in rs], marker="o", label=case)
        wall = [float(r["bake_cpu_s"]) for r in rs]
        tx.plot(b, wall, marker="o", label=case)
        for k, w in zip(b, wall):
            tx.annotate(f"{w / wall[0]:.2f}x", (k, w), textcoords="offset points",
                        xytext=(4, -12), fontsize=8)
        es = [e for e in energy if e["case"] == case]
        gx.plot([int(e["bounce"]) for e in es], [float(e["rms_ratio"]) for e in es], marker="o",
                label=case)
    ex.set_ylabel("relit error vs the 8-bounce path-traced reference (% rel. RMS)")
    ex.set_title("error against bounces B (grace.hdr, 256 terms)")
    tx.set_ylabel("bake CPU seconds (all threads; wall time is in the CSV)")
    tx.set_title("bake time against B (x: against B = 0)")
    gx.set_yscale("log")
    gx.set_ylabel("sqrt(E_b / E_0), E_b = sum of T_b^2")
    gx.set_title("energy of each bounce (B = 4 store)")
    for a in (ex, tx, gx):
        a.set_xlabel("bounces B" if a is not gx else "bounce b")
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    os.makedirs(png_dir, exist_ok=True)
    out = os.path.join(png_dir, "bounces.png")
    fig.savefig(out, dpi=90)
    print(f"charts_bounces.py: wrote {out}")


if __name__ == "__main__":
    main()
