"""Every runtime from Python: a visibility store relit through a BRDF (the
triple product) and a plane store lit by near-field area lights give the
same floats as `wavebake relight` writes to its .exr (read by a reader that
shares no code with either); eval for both equals `wavebake eval --json`;
exposure is the documented 2**stops; sequences are generators whose
frames are the single relights; the errors say what is wrong."""
import inspect
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import wavebake
from test_relight import read_exr_zip_float

BIN = os.environ.get("WB_WAVEBAKE_BIN", "")
SOFTBOX = Path(os.environ.get("WB_SOURCE_DIR", ".")) / "docs" / "lights" / "softbox.json"


@pytest.fixture(scope="session")
def shaded(tmp_path_factory):
    """A visibility store (camera), a visibility store with a mesh layout and
    a plane:4 store, small."""
    root = tmp_path_factory.mktemp("shaded")
    small = dict(light_res=8, tile_size=8, column_group=128)
    out = {"vis": root / "vis.wbk", "mesh": root / "mesh.wbk", "plane": root / "plane.wbk"}
    for job in (wavebake.bake("builtin:sphere-plane", out["vis"], workers=2, layout="camera:16x16",
                              transport="visibility", **small),
                wavebake.bake("builtin:sphere-plane", out["mesh"], workers=2, layout="hilbert:128x64",
                              transport="visibility", **small),
                wavebake.bake("builtin:furnace", out["plane"], workers=2, layout="camera:16x16",
                              light_res=16, light_domain="plane:4", tile_size=8, column_group=128)):
        assert job["phase"] == "DONE", job
    return out


def cli(*args):
    return subprocess.run([BIN, *map(str, args)], check=True, capture_output=True, text=True).stdout


def assert_same_floats(ours, theirs):
    assert ours.shape == theirs.shape
    np.testing.assert_array_equal(np.isnan(ours), np.isnan(theirs))
    mask = ~np.isnan(ours)
    assert mask.sum() > 50 and np.abs(ours[mask]).max() > 0
    np.testing.assert_array_equal(ours[mask], theirs[mask])


def test_glossy_equals_the_command_line(shaded, tmp_path):
    probe = Path(os.environ["WB_SHARED_DATA"]) / "probes" / "grace.hdr"
    for brdf, terms, rotate in (("phong:16", 64, 30), ("blinn:64", 256, 0)):
        out = tmp_path / f"{brdf.replace(':', '_')}.exr"
        cli("relight", shaded["vis"], "--env", probe, "--brdf", brdf, "--terms", terms,
            "--rotate", rotate, "--out", out)
        ours = wavebake.relight(shaded["vis"], probe, terms=terms, rotate=rotate, brdf=brdf)
        assert_same_floats(ours, read_exr_zip_float(out))
    lambert = wavebake.relight(shaded["vis"], probe, terms=64)
    glossy = wavebake.relight(shaded["vis"], probe, terms=64, brdf="phong:16")
    mask = ~np.isnan(lambert)
    assert np.abs(lambert[mask] - glossy[mask]).max() > 1e-3  # the BRDF matters


def test_near_field_equals_the_command_line(shaded, tmp_path):
    out = tmp_path / "near.exr"
    cli("relight", shaded["plane"], "--area-light", SOFTBOX, "--out", out)
    ours = wavebake.relight(shaded["plane"], area_lights=[SOFTBOX])
    assert_same_floats(ours, read_exr_zip_float(out))
    fewer = wavebake.relight(shaded["plane"], area_lights=[SOFTBOX], target_fraction=0.05)
    assert not np.array_equal(np.nan_to_num(fewer), np.nan_to_num(ours))


def test_exposure_is_two_to_the_stops(shaded):
    base = wavebake.relight(shaded["vis"], "builtin:sky", terms=64, brdf="phong:16")
    brighter = wavebake.relight(shaded["vis"], "builtin:sky", terms=64, brdf="phong:16", exposure=1)
    mask = ~np.isnan(base)
    np.testing.assert_array_equal(brighter[mask], 2 * base[mask])


def test_numpy_environment_for_a_glossy_store(shaded):
    ones = np.ones((16, 32, 3), np.float32)
    a = wavebake.relight(shaded["vis"], ones, terms=10**6, brdf="phong:16")
    b = wavebake.relight(shaded["vis"], "builtin:constant", terms=10**6, brdf="phong:16")
    mask = ~np.isnan(b)
    np.testing.assert_allclose(a[mask], b[mask], rtol=1e-5)


def test_view_of_a_mesh_layout(shaded):
    with pytest.raises(wavebake.InvalidArgument, match="view"):
        wavebake.relight(shaded["mesh"], "builtin:sky", brdf="phong:32")  # no eye given
    near = wavebake.relight(shaded["mesh"], "builtin:sky", brdf="phong:32", view=(0, 1, 3))
    far = wavebake.relight(shaded["mesh"], "builtin:sky", brdf="phong:32", view=(3, 1, 0))
    mask = ~np.isnan(near)
    assert mask.sum() > 50 and np.abs(near[mask] - far[mask]).max() > 1e-4  # the view matters
    with pytest.raises(wavebake.InvalidArgument, match="view"):
        wavebake.relight(shaded["vis"], "builtin:sky", view=(0, 1, 3))  # a camera layout's own eye


def test_sequences_are_generators_of_the_single_frames(shaded, tmp_path):
    frames = wavebake.relight_sequence(shaded["vis"], "builtin:sky", rotate=[0, 90],
                                       brdf=["phong:16", "phong:64"], terms=64)
    assert inspect.isgenerator(frames)
    got = list(frames)
    assert len(got) == 2
    for frame, (rotate, brdf) in zip(got, ((0, "phong:16"), (90, "phong:64"))):
        single = wavebake.relight(shaded["vis"], "builtin:sky", terms=64, rotate=rotate, brdf=brdf)
        np.testing.assert_array_equal(np.isnan(frame), np.isnan(single))
        np.testing.assert_array_equal(frame[~np.isnan(frame)], single[~np.isnan(single)])
    sequence = tmp_path / "seq.json"
    sequence.write_text(json.dumps({"frames": 2, "from": {"centre": [0, 0], "height": 1, "size": [0.5, 0.5]},
                                    "to": {"height": 2}}))
    moving = list(wavebake.relight_sequence(shaded["plane"], area_light_sequence=sequence))
    assert len(moving) == 2
    mask = ~np.isnan(moving[0])
    assert np.nansum(moving[0]) > np.nansum(moving[1]) > 0  # the light rises away
    with pytest.raises(wavebake.InvalidArgument, match="brdf"):
        list(wavebake.relight_sequence(shaded["vis"], "builtin:sky", rotate=[0, 1], brdf=["phong:2"]))


def test_eval_of_glossy_and_area_lights_is_the_command_lines(shaded):
    ours = wavebake.eval(shaded["vis"], "builtin:sky", terms=64, brdf="phong:16", dense=False,
                         target_rel_se=0.02)
    theirs = json.loads(cli("eval", shaded["vis"], "--env", "builtin:sky", "--terms", 64,
                            "--brdf", "phong:16", "--no-dense", "--reference-se", 0.02, "--json"))
    assert ours["compressed"]["rel_rms"] == pytest.approx(theirs["compressed"]["rel_rms"], rel=1e-9)
    assert ours["reference"]["rays"] == theirs["reference"]["rays"]
    near = wavebake.eval(shaded["plane"], area_lights=[SOFTBOX], reference_batches=4)
    cli_near = json.loads(cli("eval", shaded["plane"], "--area-light", SOFTBOX, "--reference-batches", 4,
                              "--json"))
    assert near["near_field"]["rel_rms"] < 0.05, near["near_field"]
    assert near["near_field"]["rel_rms"] == pytest.approx(cli_near["near_field"]["rel_rms"], rel=1e-9)
    few = wavebake.eval(shaded["vis"], "builtin:sky", reference=False, terms=8, brdf="phong:16")
    assert few["terms"] == 8 and 0 < few["vs_all_lights"]["rel_rms"] < 1


def test_shading_errors_are_named(shaded, stores):
    with pytest.raises(wavebake.FailedPrecondition, match="visibility"):
        wavebake.relight(stores["furnace"], "builtin:sky", brdf="phong:16")  # a diffuse store
    with pytest.raises(wavebake.InvalidArgument, match="brdf"):
        wavebake.relight(shaded["vis"], "builtin:sky", brdf="velvet")
    with pytest.raises(wavebake.InvalidArgument, match="^env"):
        wavebake.relight(shaded["plane"], "builtin:sky", area_lights=[SOFTBOX])
    with pytest.raises(wavebake.InvalidArgument, match="^env"):
        wavebake.relight(shaded["vis"])
    with pytest.raises(wavebake.InvalidArgument, match="^exposure"):
        wavebake.relight(shaded["vis"], "builtin:sky", exposure=float("inf"))
