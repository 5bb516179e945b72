"""The installed package: imported from site-packages (not the build tree),
its version the CMake project's, its extension loadable anywhere, and its
stub (__init__.pyi) the module's own types: every public name, parameter,
default and annotation of the module is the stub's, every parameter is
named in the extension (py::arg) and in the docstring, and pathlib.Path
works wherever a path goes."""
import ast
import importlib.metadata
import importlib.util
import inspect
import os
import re
import shutil
import subprocess
import sys
import typing
import unittest.mock
from importlib.machinery import SourceFileLoader
from pathlib import Path

import numpy as np
import pytest

import wavebake
from wavebake import _wavebake

PACKAGE = Path(wavebake.__file__).parent
STUB = PACKAGE / "__init__.pyi"


STUB_OVERLOADS = {}


def load_stub():
    """The stub as a module; its @overload functions recorded by qualified
    name (typing.overload would leave only a placeholder behind)."""
    def recording(f):
        STUB_OVERLOADS.setdefault(f.__qualname__, []).append(f)
        return f

    loader = SourceFileLoader("wavebake_stub_under_test", str(STUB))
    spec = importlib.util.spec_from_loader(loader.name, loader)
    module = importlib.util.module_from_spec(spec)
    with unittest.mock.patch.object(typing, "overload", recording):
        loader.exec_module(module)
    return module


def stub_public_names():
    names = set()
    for node in ast.parse(STUB.read_text()).body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
    return {n for n in names if not n.startswith("_") or n == "__version__"}


def test_installed_not_the_build_tree():
    assert "site-packages" in wavebake.__file__, wavebake.__file__
    assert "site-packages" in _wavebake.__file__, _wavebake.__file__
    assert (PACKAGE / "py.typed").exists() and STUB.exists()


def test_version_is_the_cmake_projects():
    assert re.fullmatch(r"\d+\.\d+\.\d+", wavebake.__version__)
    # Two routes from CMakeLists.txt: setup.py's metadata and the compile definition.
    assert importlib.metadata.version("wavebake") == wavebake.__version__
    source = os.environ.get("WB_SOURCE_DIR")
    if source:
        text = (Path(source) / "CMakeLists.txt").read_text()
        assert f"project(wavebake VERSION {wavebake.__version__}" in text


def test_extension_loads_outside_the_build_tree():
    """Every library it needs resolves without the build directory."""
    ldd = subprocess.run(["ldd", _wavebake.__file__], capture_output=True, text=True, check=True).stdout
    assert "not found" not in ldd, ldd
    build = os.environ.get("WB_BINARY_DIR")
    if build:
        assert os.path.realpath(build) not in ldd
        readelf = subprocess.run(["readelf", "-d", _wavebake.__file__], capture_output=True, text=True).stdout
        assert os.path.realpath(build) not in readelf


def compare(ours, theirs, where):
    a, b = inspect.signature(ours), inspect.signature(theirs)
    assert list(a.parameters) == list(b.parameters), where
    for name in a.parameters:
        p, q = a.parameters[name], b.parameters[name]
        assert (p.kind, p.default, p.annotation) == (q.kind, q.default, q.annotation), (where, name)
    assert a.return_annotation == b.return_annotation, where


def compare_callable(ours, theirs, where):
    overloads = STUB_OVERLOADS.get(theirs.__qualname__)
    if overloads:
        mine = typing.get_overloads(ours)
        assert len(mine) == len(overloads), where
        for m, o in zip(mine, overloads):
            compare(m, o, where)
    else:
        compare(ours, theirs, where)


def test_the_stub_is_the_module():
    stub = load_stub()
    assert set(wavebake.__all__) == stub_public_names()
    for name in wavebake.__all__:
        ours = getattr(wavebake, name)
        if name not in vars(stub):  # declared only: `__version__: str`
            assert type(ours).__name__ == stub.__annotations__[name], name
            continue
        theirs = getattr(stub, name)
        if inspect.isfunction(theirs):
            compare_callable(ours, theirs, name)
        elif inspect.isclass(theirs) and issubclass(theirs, BaseException):
            assert [b.__name__ for b in ours.__bases__] == [b.__name__ for b in theirs.__bases__], name
        elif inspect.isclass(theirs):
            assert inspect.isclass(ours), name
            public = {n for n in dir(ours) if not n.startswith("_")}
            declared = {n for n in vars(theirs) if not n.startswith("_")}
            assert public == declared, (name, public ^ declared)
            for member, value in vars(theirs).items():
                if isinstance(value, property):
                    assert isinstance(inspect.getattr_static(ours, member), property), (name, member)
                elif inspect.isfunction(value) and (not member.startswith("_") or member == "__init__"):
                    compare_callable(getattr(ours, member), value, f"{name}.{member}")
                elif inspect.isfunction(value):
                    assert callable(getattr(ours, member, None)), (name, member)


def public_callables():
    for name in wavebake.__all__:
        obj = getattr(wavebake, name)
        if inspect.isfunction(obj):
            yield name, obj
        elif inspect.isclass(obj):
            for member, value in vars(obj).items():
                if inspect.isfunction(value) and (not member.startswith("_") or member == "__init__"):
                    yield f"{name}.{member}", value


def test_every_parameter_is_documented():
    for where, f in public_callables():
        doc = inspect.getdoc(f) if not where.endswith("__init__") else inspect.getdoc(
            getattr(wavebake, where.split(".")[0]))
        assert doc, where
        for p in inspect.signature(f).parameters:
            if p != "self":
                assert re.search(rf"\b{p}\b", doc), (where, p)


def extension_parameters(f):
    """The parameter names in a pybind11 docstring's signature line."""
    first = f.__doc__.splitlines()[0] if f.__doc__.startswith(f.__name__) else f.__doc__.splitlines()[1]
    inside = first[first.index("(") + 1:first.rindex(")")]
    return [part.split(":")[0].strip() for part in re.split(r",\s*(?![^\[]*\])", inside) if part.strip()]


def test_the_extension_names_its_parameters():
    """py::arg on every binding: no arg0, and the Python layer calls the
    extension by the same names."""
    for name in ("relight", "eval", "export"):
        params = extension_parameters(getattr(_wavebake, name))
        assert params == list(inspect.signature(getattr(wavebake, name)).parameters), name
    assert extension_parameters(_wavebake.bake)[:3] == ["scene", "out", "workers"]
    for cls in (_wavebake.Store, _wavebake.Client):
        for member, value in vars(cls).items():
            if member.startswith("_") and member != "__init__":
                continue
            if callable(value) and getattr(value, "__doc__", None):
                params = extension_parameters(value)
                assert not any(re.fullmatch(r"arg\d+", p) for p in params), (cls, member, params)
    for member in ("column",):
        assert extension_parameters(_wavebake.Store.column) == ["self", "index", "domain"]
    for member in ("watch", "status", "jobs", "cancel", "fetch"):
        ours = [p for p in inspect.signature(getattr(wavebake.Client, member)).parameters]
        assert extension_parameters(getattr(_wavebake.Client, member)) == ours, member


def test_paths_are_accepted_everywhere(stores, tmp_path):
    path = Path(stores["furnace"])
    store = wavebake.Store(path)
    assert store.path == str(path)
    probe = Path(os.environ["WB_SHARED_DATA"]) / "probes" / "grace.hdr"
    by_path = wavebake.relight(path, probe, terms=16)
    by_str = wavebake.relight(str(path), str(probe), terms=16)
    np.testing.assert_array_equal(np.isnan(by_path), np.isnan(by_str))
    mask = ~np.isnan(by_str)
    np.testing.assert_array_equal(by_path[mask], by_str[mask])
    report = wavebake.eval(path, probe, reference=False, terms=16)
    assert report["terms"] == 16
    out = tmp_path / "baked.wbk"
    job = wavebake.bake("builtin:furnace", out, workers=1, light_res=8, layout="camera:8x8", tile_size=8)
    assert Path(wavebake.Store(out).path) == out and job["tasks_done"] == job["tasks_total"]


def test_the_example_type_checks_under_mypy_strict(tmp_path):
    """docs/python_example.py against the installed stub, as a user's
    editor or CI would check their code."""
    source = os.environ.get("WB_SOURCE_DIR")
    if not source:
        pytest.skip("WB_SOURCE_DIR names the source tree")
    mypy = shutil.which("mypy") or "/usr/bin/mypy"
    run = subprocess.run([mypy, "--strict", "--python-executable", sys.executable, "--cache-dir",
                          str(tmp_path / "cache"), str(Path(source) / "docs" / "python_example.py")],
                         capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
