"""wavebake.export: the same wavelet-tree textures, byte for byte, as
`wavebake export` writes for the same store and options, and the same
header but for its timing; the errors name the argument."""
import json
import os
import subprocess
from pathlib import Path

import pytest

import wavebake

ARRAYS = ("line.bin", "blocks.bin", "cells.bin")


def cli_export(store, out, *flags):
    subprocess.run([os.environ["WB_WAVEBAKE_BIN"], "export", str(store), "--format", "wavelet-tree",
                    "--out", str(out), *map(str, flags)], check=True, capture_output=True, text=True)
    return json.loads((out / "header.json").read_text())


def without_timing(header):
    header = json.loads(json.dumps(header))
    header["stats"].pop("seconds")
    return header


@pytest.mark.parametrize("options, flags", [
    ({}, ()),
    ({"target_error": 0.05, "bits": 9}, ("--target-error", 0.05, "--bits", 9)),
    ({"cut_off": 0.001, "bits": [8, 6, 5], "jump_nodes": 2},
     ("--cut-off", 0.001, "--bits", "8,6,5", "--jump-nodes", 2)),
])
def test_equals_the_command_line(stores, tmp_path, options, flags):
    ours_dir, theirs_dir = tmp_path / "py", tmp_path / "cli"
    store = wavebake.Store(stores["cubes-wall"])  # a Store works as well as a path
    header = wavebake.export(store, ours_dir, **options)
    theirs = cli_export(stores["cubes-wall"], theirs_dir, *flags)
    assert without_timing(header) == without_timing(theirs)
    assert header == json.loads((ours_dir / "header.json").read_text())
    for name in ARRAYS:
        ours, cli = (ours_dir / name).read_bytes(), (theirs_dir / name).read_bytes()
        assert len(ours) > 0 and ours == cli, name
    assert header["stats"]["nodes_kept"] > 0
    bits = options.get("bits")
    levels = header["levels"]
    assert header["code_bits"] == ([bits] * levels if isinstance(bits, int) else bits or
                                   {5: [9, 9, 6, 5, 4], 3: [6, 5, 4]}.get(levels)), header
    assert header["settings"]["jump_nodes"] == options.get("jump_nodes", 16)


def test_errors_name_the_argument(stores, tmp_path):
    store = Path(stores["cubes-wall"])
    with pytest.raises(wavebake.InvalidArgument, match="^format: "):
        wavebake.export(store, tmp_path / "a", format="dds")  # type: ignore[arg-type]
    with pytest.raises(wavebake.InvalidArgument, match="^cut_off: "):
        wavebake.export(store, tmp_path / "a", cut_off=0.1, target_error=0.1)
    with pytest.raises(wavebake.InvalidArgument, match="^cut_off: "):
        wavebake.export(store, tmp_path / "a", cut_off=float("nan"))
    with pytest.raises(wavebake.InvalidArgument, match="^target_error: "):
        wavebake.export(store, tmp_path / "a", target_error=-1)
    for bits in (12, [8, 8], "x", [1.5]):
        with pytest.raises(wavebake.InvalidArgument, match="^bits: "):
            wavebake.export(store, tmp_path / "a", bits=bits)  # type: ignore[arg-type]
    with pytest.raises(wavebake.InvalidArgument, match="^jump_nodes: "):
        wavebake.export(store, tmp_path / "a", jump_nodes=0)
    with pytest.raises(wavebake.NotFound):
        wavebake.export(tmp_path / "missing.wbk", tmp_path / "a")
    assert not (tmp_path / "a").exists()
