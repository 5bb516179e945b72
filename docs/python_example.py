"""A short tour of `import wavebake` (docs/python.md shows it cell by cell
with its output). Run from a build tree:

    PYTHONPATH=build/python /usr/bin/python3 docs/python_example.py [OUT_DIR]
"""
import os
import sys
from pathlib import Path

import numpy as np

import wavebake

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out")
out.mkdir(parents=True, exist_ok=True)
probe = str(Path(os.environ.get("WB_SHARED_DATA", "../shared/data")) / "probes" / "grace.hdr")

# 1. Bake a built-in scene in this process (as `wavebake bake`).
store_path = out / "cubes.wbk"
if not store_path.exists():
    job = wavebake.bake("builtin:cubes-wall", str(store_path), layout="camera:64x64", light_res=16)
    print(job["phase"], job["tasks_done"], "tasks,", job["rays_traced"], "rays")

# 2. Open it: metadata, statistics, samples.
store = wavebake.Store(str(store_path))
print(store)
stats = store.attrs["stats"]
print(f"{stats['nnz']} coefficients kept, {stats['bytes']['bits_per_value']:.2f} bits per value, "
      f"{stats['bytes']['compression_ratio']:.1f}x smaller than float32")
print("columns by transform depth:", stats["depth_histogram"])
grid = store.samples["grid"]
print("samples:", int((grid >= 0).sum()), "of", grid.size, "cells")

# 3. Relight under a probe, turned 30 degrees: an (H, W, 3) float32 array.
image = wavebake.relight(store, probe, terms=256, rotate=30)
print(image.shape, image.dtype, "mean RGB", np.nanmean(image, axis=(0, 1)).round(4))

# 4. What n wavelet lights cost against all of them, and the store against
#    an independently traced reference.
for n in (16, 64, 256, 1024):
    e = wavebake.eval(store, probe, reference=False, terms=n)["vs_all_lights"]
    print(f"{n:5d} lights: {100 * e['rel_rms']:5.2f} % relative RMS vs all {store.columns}")
report = wavebake.eval(store, probe, reference=True, terms=256)
print(f"vs the reference: dense T {100 * report['dense']['rel_rms']:.2f} %, "
      f"store at 256 lights {100 * report['compressed']['rel_rms']:.2f} %")

# 5. One column of T decoded to an image of the grid (light 0: +X face, corner texel).
column = store.column(0)
print("column 0:", column.shape, "sum", float(column.sum()).__round__(5))

# 6. A strip of frames as the environment turns (matplotlib, if present).
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 4, figsize=(10, 2.8))
    for ax, degrees in zip(axes, (0, 90, 180, 270)):
        frame = np.nan_to_num(wavebake.relight(store, probe, terms=256, rotate=degrees))
        ax.imshow(np.clip(frame, 0, 1) ** (1 / 2.2))
        ax.set_title(f"{degrees} deg")
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(out / "python_relight.png", dpi=80)
    print("wrote", out / "python_relight.png")
except ImportError:
    pass
