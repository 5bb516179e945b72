"""Errors by kind: wavebake.Error's subclasses stand for the status codes
(and derive from the built-in exception a Python caller would catch), and
the messages name the Python argument, never a command-line flag or the
code's own spelling."""
import json
import shutil

import numpy as np
import pytest

import wavebake


def test_the_hierarchy():
    assert issubclass(wavebake.InvalidArgument, ValueError)
    assert issubclass(wavebake.OutOfRange, ValueError)
    assert issubclass(wavebake.NotFound, FileNotFoundError)
    assert issubclass(wavebake.AlreadyExists, FileExistsError)
    assert issubclass(wavebake.Unavailable, ConnectionError)
    assert issubclass(wavebake.DeadlineExceeded, TimeoutError)
    codes = set()
    for name in wavebake.__all__:
        cls = getattr(wavebake, name)
        if isinstance(cls, type) and issubclass(cls, wavebake.Error) and cls is not wavebake.Error:
            codes.add(cls.code)
    assert len(codes) == 16  # every code of absl::StatusCode but OK


def test_missing_store_is_not_found(tmp_path):
    missing = tmp_path / "nothing.wbk"
    with pytest.raises(wavebake.NotFound) as e:
        wavebake.Store(missing)
    assert isinstance(e.value, FileNotFoundError)
    assert "nothing.wbk" in str(e.value)
    assert not str(e.value).startswith("NOT_FOUND")


def test_bad_arguments_are_invalid_argument(stores):
    s = wavebake.Store(stores["furnace"])
    with pytest.raises(wavebake.InvalidArgument, match="^terms"):
        wavebake.relight(s, "builtin:sky", terms=0)
    with pytest.raises(wavebake.InvalidArgument, match="^env"):
        wavebake.relight(s, np.ones((4, 4, 3)))
    with pytest.raises(wavebake.InvalidArgument, match="^light_res"):
        wavebake.bake("builtin:furnace", "never.wbk", light_res=33)
    with pytest.raises(wavebake.InvalidArgument, match="^lightres"):
        wavebake.bake("builtin:furnace", "never.wbk", lightres=8)


def test_a_corrupt_store_is_data_loss(stores, tmp_path):
    copy = tmp_path / "corrupt.wbk"
    shutil.copytree(stores["furnace"], copy)
    zarray = copy / "transport" / "depth" / ".zarray"
    spec = json.loads(zarray.read_text())
    spec["dtype"] = "<i4"  # a dtype the reader knows, not the documented uint8
    zarray.write_text(json.dumps(spec))
    with pytest.raises(wavebake.DataLoss, match="depth"):
        wavebake.relight(copy, "builtin:sky")
