"""A store does not depend on where its scene was baked from: one scene
file baked from two directories gives stores equal byte for byte, naming
the scene by file name and content hash; the runtime finds the file beside
the store or along WAVEBAKE_SCENE_PATH."""
import json
import os
from pathlib import Path

import pytest

import wavebake

TENT = "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 0.6 0\nf 1 3 2\nf 1 4 3\nf 1 2 5\nf 2 3 5\n"


def files(store):
    return {p.relative_to(store): p.read_bytes() for p in sorted(store.rglob("*")) if p.is_file()}


def test_one_scene_from_two_directories(tmp_path, monkeypatch):
    stores = []
    for where in ("alice/models", "bob/elsewhere/deep"):
        scene = tmp_path / where / "tent.obj"
        scene.parent.mkdir(parents=True)
        scene.write_text(TENT)
        monkeypatch.chdir(scene.parent.parent)  # a relative path once, then another
        out = tmp_path / f"{where.split('/')[0]}.wbk"
        job = wavebake.bake(Path(scene.parent.name) / "tent.obj", out, workers=2, light_res=8,
                            layout="hilbert:4x4", tile_size=8)
        assert job["phase"] == "DONE", job
        stores.append(out)
    a, b = files(stores[0]), files(stores[1])
    assert a.keys() == b.keys() and len(a) > 10
    assert [k for k in a if a[k] != b[k]] == []
    attrs = json.loads(a[Path(".zattrs")])
    assert attrs["scene"] == "tent.obj"
    assert len(attrs["scene_hash"]) >= 32
    assert str(tmp_path) not in a[Path(".zattrs")].decode()


def test_the_runtime_finds_the_scene(tmp_path, monkeypatch):
    models = tmp_path / "models"
    models.mkdir()
    (models / "tent.obj").write_text(TENT)
    store = tmp_path / "stores" / "tent.wbk"
    store.parent.mkdir()
    wavebake.bake(models / "tent.obj", store, workers=2, light_res=8, layout="hilbert:4x4", tile_size=8)
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("WAVEBAKE_SCENE_PATH", raising=False)
    with pytest.raises(wavebake.Error, match="tent.obj"):  # eval retraces the scene
        wavebake.eval(store, "builtin:sky", terms=16, dense=False, target_rel_se=0.05)
    monkeypatch.setenv("WAVEBAKE_SCENE_PATH", str(models))
    report = wavebake.eval(store, "builtin:sky", terms=16, dense=False, target_rel_se=0.05)
    assert report["compressed"]["rel_rms"] < 0.5
