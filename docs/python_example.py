"""A tour of `import wavebake`. docs/python.md is this file, cell by cell
(`# %% Title`; a cell's leading `# ` lines are its prose), each with what it
printed: docs/python_md.py runs it and writes the page. Run it alone with
the installed package (README: Python):

    v/bin/python docs/python_example.py [OUT_DIR]

It type-checks under `mypy --strict` against the package's stub.
"""
# %% Setup
# The package's own types (`wavebake/__init__.pyi`, `py.typed`) and its
# version, the CMake project's.
import os
import sys
from pathlib import Path

import numpy as np

import wavebake

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out")
out.mkdir(parents=True, exist_ok=True)
data = Path(os.environ.get("WB_SHARED_DATA", "../shared/data"))
probe = data / "probes" / "grace.hdr"
print("wavebake", wavebake.__version__)

# %% Bake a store in this process
# Keyword arguments are the fields of `BakeRequest` (`proto/wavebake.proto`):
# `light_res`, `layout`, `target_error`, `column_mode`, `bits`, `seed`,
# `transport`, `light_domain`, … A wrong name or value raises
# `wavebake.InvalidArgument` (a `ValueError`) naming it, a wrong type
# `TypeError`. The job comes back as a dict: the `Job` message in the same
# JSON shape as `wavebake status --json` and the monitor's `/api/jobs`
# (phases as `DONE`, numbers as numbers). Ctrl-C cancels the bake and
# leaves nothing at the output.
store_path = out / "cubes.wbk"
if not store_path.exists():
    job = wavebake.bake("builtin:cubes-wall", store_path, layout="camera:64x64", light_res=16)
    print(job["phase"], job["tasks_done"], "tasks,", job["rays_traced"], "rays")

# %% Open it
# `store.attrs` is the root `.zattrs`, `store.params` the bake's parameters,
# `store.samples` a dict of numpy arrays (`grid` (H, W), `position`,
# `normal`, `albedo` (S, 3), `vertex` for mesh layouts). Paths are `str` or
# `pathlib.Path` everywhere.
store = wavebake.Store(store_path)
print(store)
stats = store.attrs["stats"]
print(f"{stats['nnz']} coefficients kept, {stats['bytes']['bits_per_value']:.2f} bits per value, "
      f"{stats['bytes']['compression_ratio']:.1f}x smaller than float32")
print("columns by transform depth:", stats["depth_histogram"])
grid = store.samples["grid"]
print("samples:", int((grid >= 0).sum()), "of", grid.size, "cells")

# %% Relight
# `env` is a spec (an `.hdr`/`.exr` path, `builtin:sky`, `builtin:constant`)
# or a lat-long numpy array of shape (H, 2H, 3); `rotate` turns it about +Y
# (+90° moves the map by −width/4 pixels). Masked cells are NaN. The floats
# are the ones `wavebake relight --out x.exr` writes.
image = wavebake.relight(store, probe, terms=256, rotate=30)
print(image.shape, image.dtype, "mean RGB", np.nanmean(image, axis=(0, 1)).round(4))
sky = np.ones((32, 64, 3), np.float32)
sky[16:] = 0.1  # a bright upper half: an environment as an array
print("array env: mean", round(float(np.nanmean(wavebake.relight(store, sky))), 4))

# %% What the approximation costs
# `reference=True` is `wavebake eval --reference --json` (an independently
# traced Monte-Carlo reference; the dense T's error is the N = 16 cubemap's
# own discretization, which the store adds almost nothing to);
# `reference=False` compares against the same frame relit with every
# wavelet light, without tracing.
for n in (16, 64, 256, 1024):
    e = wavebake.eval(store, probe, reference=False, terms=n)["vs_all_lights"]
    print(f"{n:5d} lights: {100 * e['rel_rms']:5.2f} % relative RMS vs all {store.columns}")
report = wavebake.eval(store, probe, reference=True, terms=256)
print(f"vs the reference: dense T {100 * report['dense']['rel_rms']:.2f} %, "
      f"store at 256 lights {100 * report['compressed']['rel_rms']:.2f} %")

# %% A column of T
# Decoded to an image of the grid (light 0: +X face, corner texel), or as
# stored: its transform depth, kept positions and values.
column = store.column(0)
depth, positions, values = store.column(0, domain="wavelet")
print("column 0:", column.shape, "sum", round(float(column.sum()), 5), "depth", depth,
      len(positions), "coefficients")

# %% GPU export
# A diffuse store's rows as Boulton's wavelet-tree textures (4.4-4.5), the
# files `wavebake export` writes and `wavebake view` serves; the header
# comes back as a dict. `target_error` (or an absolute `cut_off`) prunes.
trees = out / "cubes-trees"
header = wavebake.export(store, trees, target_error=0.02)
stats = header["stats"]
print(f"{stats['trees']} trees, {100 * stats['nodes_kept'] / stats['nodes_total']:.1f}% of nodes kept,",
      f"pruned rows' error {stats['rel_error_pruned']:.4f};", sorted(p.name for p in trees.iterdir()))

# %% Glossy: a visibility store through a BRDF
# `transport="visibility"` keeps V alone in the rows; `brdf=` (`phong:E`,
# `blinn:E`, `ggx:ALPHA`, `lambert`) is applied at relight time by the
# triple product; `view=(x, y, z)` gives the eye of a mesh layout (a camera
# layout sees from its camera). `exposure` scales by 2**stops.
glossy_path = out / "sphere_vis.wbk"
if not glossy_path.exists():
    wavebake.bake("builtin:sphere-plane", glossy_path, layout="camera:64x64", light_res=16,
                  transport="visibility")
for brdf in ("lambert", "phong:8", "phong:64"):
    frame = wavebake.relight(glossy_path, probe, terms=256, brdf=brdf, exposure=1)
    print(f"{brdf:9s} mean {float(np.nanmean(frame)):.4f}  max {float(np.nanmax(frame)):.3f}")

# %% Near-field area lights
# A store baked with `light_domain="plane:S"` relights under planar area
# lights near the scene (`docs/lights/*.json`; their lights add), and
# `eval` measures them against a reference traced over their area.
plane_path = out / "cubes_plane.wbk"
softbox = Path(__file__).resolve().parent / "lights" / "softbox.json"
if not plane_path.exists():
    wavebake.bake("builtin:cubes-wall", plane_path, layout="camera:64x64", light_res=16,
                  light_domain="plane:4")
near = wavebake.relight(plane_path, area_lights=[softbox])
print("near field: mean", round(float(np.nanmean(near)), 4))
near_report = wavebake.eval(plane_path, area_lights=[softbox], reference_batches=4)
print(f"vs its reference: {100 * near_report['near_field']['rel_rms']:.2f} % relative RMS, "
      f"treated as distant {100 * near_report['distant']['rel_rms']:.2f} %")

# %% Sequences are generators
# Frames one at a time, the store opened once: a rotation, a BRDF per frame
# (material editing), or a moving area light (`area_light_sequence=`).
turns = np.linspace(0, 270, 4)
frames = list(wavebake.relight_sequence(store, probe, rotate=turns, terms=256))
print(len(frames), "frames, means", [round(float(np.nanmean(f)), 4) for f in frames])
try:
    import matplotlib  # type: ignore[import]
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # type: ignore[import]
    fig, axes = plt.subplots(1, 4, figsize=(10, 2.8))
    for ax, degrees, frame in zip(axes, turns, frames):
        ax.imshow(np.clip(np.nan_to_num(frame), 0, 1) ** (1 / 2.2))
        ax.set_title(f"{degrees:.0f} deg")
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(out / "python_relight.png", dpi=80)
    print("wrote", out / "python_relight.png")
except ImportError:
    pass

# %% Errors by kind
# Every failure is a `wavebake.Error`; its subclass names the kind
# (`InvalidArgument` is a `ValueError`, `NotFound` a `FileNotFoundError`,
# `AlreadyExists` a `FileExistsError`, `DataLoss`, `Cancelled`,
# `Unavailable`, …), and the message names the argument.
try:
    wavebake.Store(out / "missing.wbk")
except wavebake.NotFound as e:
    print(type(e).__name__, e.code, isinstance(e, FileNotFoundError), "-", e)
try:
    wavebake.relight(store, probe, terms=0)
except ValueError as e:
    print(type(e).__name__, "-", e)
