"""wavebake.eval: the same report as `wavebake eval --json` (the independent
Monte-Carlo reference), and the cheap comparison against all wavelet
lights."""
import json
import os
import subprocess

import pytest

import wavebake


def test_reference_report_matches_the_command_line(stores):
    path = str(stores["furnace"])
    report = wavebake.eval(path, "builtin:constant", reference=True, terms=64)
    assert set(report) >= {"terms", "dense", "compressed", "reference"}
    assert report["terms"] == 64
    # The furnace: B = 1; both the dense T and the store come close to the reference.
    assert report["dense"]["rel_rms"] < 0.03
    assert report["compressed"]["rel_rms"] < 0.03
    cli = subprocess.run([os.environ["WB_WAVEBAKE_BIN"], "eval", path, "--env", "builtin:constant",
                          "--reference", "--terms", "64", "--json"], capture_output=True, text=True, check=True)
    theirs = json.loads(cli.stdout)
    assert theirs["terms"] == report["terms"]
    # Same store, lighting and seeded reference: the same errors.
    for part in ("dense", "compressed"):
        for key in ("rel_rms", "max_abs"):
            assert theirs[part][key] == pytest.approx(report[part][key], rel=1e-9), (part, key)
    assert theirs["reference"]["rays"] == report["reference"]["rays"]


def test_against_all_wavelet_lights(stores):
    s = wavebake.Store(str(stores["cubes-wall"]))
    full = wavebake.eval(s, "builtin:sky", reference=False, terms=s.columns)
    assert full["vs_all_lights"]["rel_rms"] < 1e-6  # every nonzero light: float rounding only
    few = wavebake.eval(s, "builtin:sky", reference=False, terms=4)
    assert few["terms"] == 4
    assert 0 < few["vs_all_lights"]["rel_rms"] < 1
    with pytest.raises(TypeError, match="spec"):
        import numpy as np
        wavebake.eval(s, np.ones((8, 16, 3)), reference=True)


def test_a_nan_in_the_store_is_an_error_not_a_perfect_score(stores, tmp_path):
    """transport/scale rewritten through zarr with one NaN (valid zstd): eval
    against all lights returned rel_rms 0.0, psnr inf."""
    import shutil
    import zarr
    damaged = tmp_path / "nan.wbk"
    shutil.copytree(stores["cubes-wall"], damaged)
    scale = zarr.open_array(str(damaged / "transport" / "scale"), mode="r+")
    column = int((scale[:] > 0).argmax())  # a column that holds coefficients
    scale[column] = float("nan")
    with pytest.raises(wavebake.DataLoss, match=rf"transport/scale\[{column}\]"):
        wavebake.eval(str(damaged), "builtin:sky", reference=False, terms=16)
    with pytest.raises(wavebake.DataLoss, match=rf"transport/scale\[{column}\]"):
        wavebake.relight(str(damaged), "builtin:sky")
