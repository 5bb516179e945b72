#!/usr/bin/python3
"""Turns the CSVs of bench_charts_data into the PNGs of docs/RESULTS.md.

    /usr/bin/python3 bench/charts.py CSV_DIR PNG_DIR

One PNG per CSV present (a chart whose CSV is missing is skipped with a
note); matplotlib's Agg backend, no display needed.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MODE_COLORS = {"2d": "tab:blue", "full": "tab:red", "adaptive": "tab:green"}
FILTER_STYLES = {"haar": "-", "legall53": "--"}


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def scenes_of(rows):
    seen = []
    for r in rows:
        if r["scene"] not in seen:
            seen.append(r["scene"])
    return seen


# Chart 1's panels, top to bottom: (x column, y column, y scale, x label, y label).
SIZE_PANELS = [
    ("matrix_rel_rms", "transport_bytes", 1e3, "relative RMS error of T (stats.matrix_rel_rms)",
     "transport bytes on disk (kB)"),
    ("matrix_rel_rms", "nnz", 1e3, "relative RMS error of T (stats.matrix_rel_rms)",
     "kept coefficients (thousands)"),
    ("grace_rel_rms", "transport_bytes", 1e3,
     "relit error under grace.hdr, all lights, vs the dense T", "transport bytes on disk (kB)"),
    ("pisa_rel_rms", "transport_bytes", 1e3,
     "relit error under pisa.hdr, all lights, vs the dense T", "transport bytes on disk (kB)"),
]


def size_error(rows, out):
    """Chart 1 (4D paper Fig. 7): bytes and kept coefficients vs matrix error,
    and bytes vs the relighting error under each probe."""
    scenes = scenes_of(rows)
    panels = [p for p in SIZE_PANELS if p[0] in rows[0]]
    fig, axes = plt.subplots(len(panels), len(scenes), figsize=(5 * len(scenes), 4 * len(panels)),
                             squeeze=False)
    for col, scene in enumerate(scenes):
        for mode, color in MODE_COLORS.items():
            for filt, style in FILTER_STYLES.items():
                # coding: uniform step (default) or the paper's 2^l scaling
                # (4D paper §4.3: the baseline, adaptive / haar only, dotted).
                for coding in ("uniform", "paper"):
                    sel = [r for r in rows
                           if r["scene"] == scene and r["mode"] == mode and r["filter"] == filt
                           and r.get("coding", "uniform") == coding]
                    if not sel:
                        continue
                    label = f"{mode} / {filt}" + (" / paper 2^l coding" if coding == "paper" else "")
                    ls = ":" if coding == "paper" else style
                    mk = "x" if coding == "paper" else "o"
                    for row, (xk, yk, scale, _, _) in enumerate(panels):
                        if yk == "nnz" and coding == "paper":
                            continue  # same coefficients either way
                        pts = sorted((float(r[xk]), float(r[yk]) / scale) for r in sel)
                        axes[row][col].plot([p[0] for p in pts], [p[1] for p in pts], ls,
                                            color=color, marker=mk, label=label)
        raw = next(int(r["raw_bytes"]) for r in rows if r["scene"] == scene)
        axes[0][col].set_title(f"{scene}  (dense float32 T: {raw / 1e6:.1f} MB)")
        for row, (_, _, _, xlabel, ylabel) in enumerate(panels):
            ax = axes[row][col]
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(xlabel)
            ax.set_ylabel(ylabel)
            ax.grid(True, which="both", alpha=0.3)
        axes[0][col].legend(fontsize=8)
    fig.suptitle("Store size vs error: column modes x column filters (bits auto, "
                 "uniform step; dotted: adaptive with the paper's 2^l coding)")
    fig.tight_layout(rect=(0, 0, 1, 0.98))
    fig.savefig(out, dpi=90)


def bits_error(rows, out):
    """Chart 5: matrix error vs fixed quantization bits, and bytes vs error
    for fixed bits (curve) against bits auto, the uniform step (star)."""
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.5))
    for mode, color in MODE_COLORS.items():
        pts = sorted((int(r["bits"]), float(r["matrix_rel_rms"]), int(r["transport_bytes"]))
                     for r in rows if r["mode"] == mode and int(r["bits"]) > 0)
        if not pts:
            continue
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "-o", color=color, label=mode)
        bx.plot([p[1] for p in pts], [p[2] / 1e3 for p in pts], "-o", color=color,
                label=f"{mode}, fixed bits {pts[0][0]}..{pts[-1][0]}")
        for r in rows:
            if r["mode"] == mode and int(r["bits"]) == 0:
                bx.plot(float(r["matrix_rel_rms"]), int(r["transport_bytes"]) / 1e3, "*",
                        color=color, markersize=14, markeredgecolor="black",
                        label=f"{mode}, bits auto (uniform step)")
    target = float(rows[0]["target"])
    ax.axhline(target, color="gray", ls=":", label=f"target {target}")
    ax.set_yscale("log")
    ax.set_xlabel("quantization bits (fixed)")
    ax.set_ylabel("relative RMS error of T")
    ax.set_title(f"{rows[0]['scene']}: error vs bits (selection at target {target})")
    bx.set_xscale("log")
    bx.set_xlabel("relative RMS error of T")
    bx.set_ylabel("transport bytes on disk (kB)")
    bx.set_title("bytes vs error: fixed bits against bits auto")
    for a in (ax, bx):
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


def depth_by_level(rows, out):
    """Chart 6 (4D paper Fig. 8): mean adaptive column depth per row level."""
    scenes = scenes_of(rows)
    fig, axes = plt.subplots(1, len(scenes), figsize=(5 * len(scenes), 4), squeeze=False)
    for col, scene in enumerate(scenes):
        ax = axes[0][col]
        targets = sorted({float(r["target"]) for r in rows if r["scene"] == scene})
        for t in targets:
            pts = sorted((int(r["row_level"]), float(r["mean_depth"]))
                         for r in rows if r["scene"] == scene and float(r["target"]) == t)
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "-o", label=f"target {t}")
        ax.set_title(f"{scene} (adaptive, haar)")
        ax.set_xlabel("row-transform level of the light (0 = scaling, coarse to fine)")
        ax.set_ylabel("mean column depth")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


VIS_STYLES = {"brute": ("tab:red", "--", "s", "brute force"),
              "refined": ("tab:blue", "-", "o", "refined")}


def by_visibility(rows):
    """Chart 2's rows split by visibility method, each sorted by N (older
    CSVs without the column are all brute force)."""
    out = {}
    for r in rows:
        out.setdefault(r.get("visibility", "brute"), []).append(r)
    for v in out.values():
        v.sort(key=lambda r: int(r["light_res"]))
    return out


def bake_time(rows, out):
    """Chart 2: brute force against visibility refinement vs N — trace and
    column-stage time, rays, store size — and the relighting error against
    the independent reference (when measured)."""
    series = by_visibility(rows)
    with_ref = "dense_ref_rel_rms" in rows[0]
    fig, axes = plt.subplots(1, 4 if with_ref else 3, figsize=(24 if with_ref else 18, 4.8))
    ax, rx, bx = axes[0], axes[1], axes[2]
    for vis, rs in series.items():
        color, ls, mk, label = VIS_STYLES.get(vis, ("gray", "-", "x", vis))
        n = [int(r["light_res"]) for r in rs]
        ax.plot(n, [float(r["bake_seconds"]) for r in rs], ls, color=color, marker=mk,
                label=f"trace, {label}")
        ax.plot(n, [float(r["column_seconds"]) for r in rs], ":", color=color, marker=mk,
                label=f"column stage + FINALIZE, {label}")
        rx.plot(n, [int(r["rays"]) / 1e6 for r in rs], ls, color=color, marker=mk, label=label)
        bx.plot(n, [int(r["transport_bytes"]) / 1e3 for r in rs], ls, color=color, marker=mk,
                label=f"{label} (matrix err "
                f"{min(float(r['matrix_rel_rms']) for r in rs):.4f}–"
                f"{max(float(r['matrix_rel_rms']) for r in rs):.4f})")
    if "brute" in series and "refined" in series:
        brute = {int(r["light_res"]): int(r["rays"]) for r in series["brute"]}
        for r in series["refined"]:
            k = int(r["light_res"])
            if k in brute and brute[k] > 0:
                rx.annotate(f"{int(r['rays']) / brute[k]:.2f}x", (k, int(r["rays"]) / 1e6),
                            textcoords="offset points", xytext=(4, -12), fontsize=8,
                            color="tab:blue")
    ax.set_ylabel(f"seconds ({rows[0]['threads']} threads)")
    ax.set_title(f"{rows[0]['scene']}: bake time vs N")
    rx.set_ylabel("rays traced (millions)")
    rx.set_title("rays: refined / brute force")
    bx.set_ylabel("transport bytes on disk (kB)")
    bx.set_title("store size vs N (adaptive, target 0.01)")
    for a in (ax, rx, bx):
        a.set_xscale("log", base=2)
        a.set_yscale("log")
        a.set_xlabel("light resolution N (M = 6N^2 columns)")
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=8, loc="upper left")
    if with_ref:
        reference_error(series, axes[3])
    fig.tight_layout()
    fig.savefig(out, dpi=90)


def relight_time(rows, out):
    """Chart 3 (4D paper Fig. 9): Eq. 8 frame time vs wavelet lights, 2d vs adaptive."""
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.5))
    series = {}
    for mode in MODE_COLORS:
        pts = sorted((int(r["terms"]), float(r["seconds"]), float(r["touched"]),
                      float(r["matrix_rel_rms"]), int(r["nnz"]))
                     for r in rows if r["mode"] == mode)
        if not pts:
            continue
        series[mode] = pts
        ax.plot([p[0] for p in pts], [p[1] * 1e3 for p in pts], "-o", color=MODE_COLORS[mode],
                label=f"{mode}: matrix err {pts[0][3]:.4f}, nnz {pts[0][4] / 1e6:.2f} M")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("wavelet lights n")
    ax.set_ylabel("ms per frame (median thread CPU time, Eq. 8 only)")
    r0 = rows[0]
    ax.set_title(f"relighting time, {r0['width']}x{r0['width']} grid, N = {r0['light_res']}")
    if "2d" in series and "adaptive" in series:
        a, b = series["2d"], series["adaptive"]
        n = [p[0] for p in a]
        bx.plot(n, [q[1] / p[1] for p, q in zip(a, b)], "-o", color="tab:green",
                label="time adaptive / 2d")
        bx.plot(n, [q[2] / p[2] for p, q in zip(a, b)], "--s", color="tab:gray",
                label="stored coefficients touched, adaptive / 2d")
        bx.axhline(1, color="black", lw=0.8)
        bx.set_xscale("log", base=2)
        bx.set_xlabel("wavelet lights n")
        bx.set_ylabel("ratio")
        bx.set_ylim(bottom=0)
        bx.set_title("adaptive against 2d at equal target error")
        bx.legend(fontsize=8)
    for x in (ax, bx):
        x.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


METHOD_COLORS = {"none": "tab:red", "basic": "tab:orange", "per-band": "tab:blue"}
METHOD_LABELS = {"none": "non-incremental", "basic": "basic incremental",
                 "per-band": "per-band incremental"}


def rotation_error(rows, out):
    """Chart 4 (Overbeck Fig. 6.2): error per frame over a rotation, three methods."""
    speeds = []
    for r in rows:
        if r["speed"] not in speeds:
            speeds.append(r["speed"])
    fig, axes = plt.subplots(2, len(speeds), figsize=(5 * len(speeds), 7.5), squeeze=False)
    for col, speed in enumerate(speeds):
        for method, color in METHOD_COLORS.items():
            pts = sorted((int(r["frame"]), float(r["image_rel_rms"]), float(r["lighting_rel_l1"]))
                         for r in rows if r["speed"] == speed and r["method"] == method)
            if not pts:
                continue
            mean = sum(p[1] for p in pts) / len(pts)
            axes[0][col].plot([p[0] for p in pts], [p[1] for p in pts], "-", color=color,
                              label=f"{METHOD_LABELS[method]} (mean {mean:.4f})")
            axes[1][col].plot([p[0] for p in pts], [p[2] for p in pts], "-", color=color,
                              label=METHOD_LABELS[method])
        terms = next(r["terms"] for r in rows if r["speed"] == speed)
        axes[0][col].set_title(f"{speed} deg/frame, {terms} wavelet lights")
        axes[0][col].set_ylabel("image rel. RMS vs all wavelet lights")
        axes[1][col].set_ylabel("lighting rel. L1 (area-weighted) |L - L~| / |L|")
        for row in (0, 1):
            ax = axes[row][col]
            ax.set_xlabel("frame")
            ax.set_yscale("log")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
    r0 = rows[0]
    fig.suptitle(f"grace.hdr rotating about +Y: cubes-wall, {r0['width']}x{r0['width']} camera "
                 f"grid, N = {r0['light_res']}, adaptive store")
    fig.tight_layout()
    fig.savefig(out, dpi=90)


def reference_error(series, ax):
    """Chart 2, last panel: rel. RMS of the relit samples vs the reference,
    brute force and refined: the trace's own dense T and its store."""
    any_rows = next(iter(series.values()))
    for vis, rs in series.items():
        color, ls, mk, label = VIS_STYLES.get(vis, ("gray", "-", "x", vis))
        n = [int(r["light_res"]) for r in rs]
        ax.plot(n, [float(r["dense_ref_rel_rms"]) for r in rs], ls, color=color, marker=mk,
                alpha=0.5, label=f"dense T, {label}")
        ax.plot(n, [float(r["store_ref_rel_rms"]) for r in rs], ls, color=color, marker=mk,
                label=f"store, all 6N^2 lights, {label}")
        ax.plot(n, [float(r["store_ref_rel_rms_256"]) for r in rs], ":", color=color, marker="^",
                label=f"store, 256 lights, {label}")
    n = [int(r["light_res"]) for r in any_rows]
    ax.plot(n, [float(r["reference_rel_se"]) for r in any_rows], ":", color="grey",
            label="reference's own rel. SE")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("light resolution N")
    ax.set_ylabel("relative RMS error vs independent reference")
    ax.set_title(f"relighting error under {any_rows[0]['env']} (target 0.01)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


LAYOUT_COLORS = {("hilbert", "64"): "tab:gray", ("uv", "128"): "tab:blue",
                 ("uv", "256"): "tab:green", ("uv", "512"): "tab:red"}


def uv_size(rows, out):
    """Chart 7: transport bytes (and bytes per sample) against matrix error,
    2d (dashed) and adaptive (solid), hilbert against uv layouts on spot.obj."""
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for (kind, side), color in LAYOUT_COLORS.items():
        for mode, style in (("2d", "--"), ("adaptive", "-")):
            pts = sorted((float(r["matrix_rel_rms"]), float(r["transport_bytes"]),
                          float(r["bytes_per_sample"])) for r in rows
                         if r["layout"] == kind and r["side"] == side and r["mode"] == mode)
            if not pts:
                continue
            label = f"{kind}:{side}² {mode}"
            axes[0].plot([p[0] for p in pts], [p[1] / 1e6 for p in pts], style, color=color,
                         marker="o", label=label)
            axes[1].plot([p[0] for p in pts], [p[2] for p in pts], style, color=color, marker="o",
                         label=label)
    for ax, ylabel in ((axes[0], "transport bytes on disk (MB)"),
                       (axes[1], "transport bytes per sample (vertex or covered texel)")):
        ax.set_xlabel("relative RMS error of T (stats.matrix_rel_rms)")
        ax.set_ylabel(ylabel)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("spot.obj, N = 32: 2d against adaptive, Hilbert vertices against lightmap texels")
    fig.tight_layout()
    fig.savefig(out, dpi=90)


def uv_fill(rows, out):
    """Chart 7b: what the uncovered texels cost, per fill, at target 0.01."""
    fills = ["zero", "push-pull", "dilate"]
    groups = []
    for r in rows:
        key = (r["side"], r["mode"])
        if key not in groups:
            groups.append(key)
    fig, ax = plt.subplots(figsize=(9, 4.5))
    width = 0.8 / len(fills)
    for i, fill in enumerate(fills):
        ys = []
        for side, mode in groups:
            match = [float(r["bytes_per_sample"]) for r in rows
                     if r["side"] == side and r["mode"] == mode and r["fill"] == fill]
            ys.append(match[0] if match else 0)
        xs = [g + (i - 1) * width for g in range(len(groups))]
        ax.bar(xs, ys, width, label=f"fill={fill}")
    ax.set_xticks(range(len(groups)))
    ax.set_xticklabels([f"uv:{side}² {mode}" for side, mode in groups])
    ax.set_ylabel("transport bytes per covered texel")
    ax.set_title("spot.obj, N = 32, target 0.01: the uncovered texels' fill before the column "
                 "transform")
    ax.legend()
    ax.grid(True, axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


PHONG_COLORS = {"phong:8": "tab:blue", "phong:32": "tab:green", "phong:128": "tab:red"}


def terms_label(t, all_terms):
    return "all" if t == 0 or t == all_terms else str(t)


def glossy_error(rows, out):
    """Chart 8 (Vollick & Lessig §6): glossy relit error vs lighting terms and BRDF terms."""
    envs = []
    for r in rows:
        if r["env"] not in envs:
            envs.append(r["env"])
    fig, axes = plt.subplots(len(envs), 2, figsize=(11, 4.2 * len(envs)), squeeze=False)
    n = int(rows[0]["light_res"])
    all_lights = 6 * n * n
    for row, env in enumerate(envs):
        for brdf, color in PHONG_COLORS.items():
            sel = [r for r in rows if r["env"] == env and r["brdf"] == brdf]
            if not sel:
                continue
            dense = float(sel[0]["rel_rms_dense"])
            # left: lighting terms at 256 BRDF terms; right: BRDF terms at 256 lighting terms
            for col, (vary, fixed) in enumerate((("light_terms", "brdf_terms"),
                                                 ("brdf_terms", "light_terms"))):
                pts = sorted((int(r[vary]) if int(r[vary]) > 0 else 10 ** 9,
                              float(r["rel_rms_ref"]), float(r["rel_rms_all"]))
                             for r in sel if int(r[fixed]) == 256)
                xs = list(range(len(pts)))
                ax = axes[row][col]
                ax.plot(xs, [p[1] for p in pts], "-o", color=color, label=f"{brdf} vs reference")
                ax.plot(xs, [p[2] for p in pts], ":", color=color,
                        label=f"{brdf} vs every term (NLA alone)")
                ax.axhline(dense, color=color, ls="--", lw=0.8)
                ax.set_xticks(xs)
                ax.set_xticklabels([terms_label(p[0] if p[0] < 10 ** 9 else 0, all_lights)
                                    for p in pts])
        for col, what in enumerate(("lighting terms (256 BRDF terms per sample)",
                                    "BRDF terms per sample (256 lighting terms)")):
            ax = axes[row][col]
            ax.set_yscale("log")
            ax.set_xlabel(what)
            ax.set_ylabel("relative RMS error")
            ax.set_title(f"{env}.hdr: dashed = dense visibility path (the N = {n} floor)")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
    r0 = rows[0]
    fig.suptitle(f"glossy triple product, sphere-plane {r0['width']}x{r0['width']} camera, "
                 f"N = {n}, visibility store (target 1 %)")
    fig.tight_layout()
    fig.savefig(out, dpi=90)


def glossy_time(rows, out):
    """Chart 8, time: one glossy frame vs lighting terms, per BRDF terms (one core)."""
    fig, axes = plt.subplots(1, len(PHONG_COLORS), figsize=(15, 4.2), squeeze=False)
    n = int(rows[0]["light_res"])
    for col, brdf in enumerate(PHONG_COLORS):
        ax = axes[0][col]
        sel = [r for r in rows if r["brdf"] == brdf]
        bts = sorted({int(r["brdf_terms"]) for r in sel}, key=lambda t: t if t > 0 else 10 ** 9)
        for i, bt in enumerate(bts):
            pts = sorted((int(r["light_terms"]), float(r["seconds"]))
                         for r in sel if int(r["brdf_terms"]) == bt)
            ax.plot([p[0] for p in pts], [p[1] * 1e3 for p in pts], "-o",
                    color=plt.cm.viridis(i / max(1, len(bts) - 1)),
                    label=f"{terms_label(bt, 0)} BRDF terms")
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xlabel("lighting terms")
        ax.set_ylabel("ms per frame (thread CPU, one core)")
        ax.set_title(f"{brdf}, grace.hdr, N = {n}")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


CHARTS = {
    "size_error": size_error,
    "bits_error": bits_error,
    "depth_by_level": depth_by_level,
    "bake_time": bake_time,
    "relight_time": relight_time,
    "rotation_error": rotation_error,
    "uv_size": uv_size,
    "uv_fill": uv_fill,
    "glossy_error": glossy_error,
    "glossy_time": glossy_time,
}


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: charts.py CSV_DIR PNG_DIR")
    csv_dir, png_dir = sys.argv[1], sys.argv[2]
    os.makedirs(png_dir, exist_ok=True)
    for name, plot in CHARTS.items():
        path = os.path.join(csv_dir, name + ".csv")
        if not os.path.exists(path):
            print(f"charts.py: {path} missing, chart skipped")
            continue
        rows = read_rows(path)
        if not rows:
            print(f"charts.py: {path} empty, chart skipped")
            continue
        out = os.path.join(png_dir, name + ".png")
        plot(rows, out)
        plt.close("all")
        print(f"charts.py: wrote {out}")


if __name__ == "__main__":
    main()
