"""wavebake.Client against a real coordinator and worker (conftest): submit,
watch as an iterator of events to the end, status, fetch a verified store
and relight it, cancel; errors named."""
import time

import numpy as np
import pytest

import wavebake

PARAMS = dict(light_res=8, layout="camera:16x16", tile_size=8, column_group=128)


def test_submit_watch_fetch_relight(coordinator, tmp_path):
    address, token = coordinator
    client = wavebake.Client(address, token_file=token)
    job = client.submit("builtin:cubes-wall", **PARAMS)
    assert job["phase"] in ("PHASE_QUEUED", "PHASE_BAKING")
    assert job["request"]["light_res"] == 8
    watch = client.watch(job["id"])
    events = list(watch)
    assert events, "no events"
    seqs = [e["seq"] for e in events if e["kind"] != "EVENT_PROGRESS"]
    assert seqs == sorted(seqs) and len(seqs) == len(set(seqs))
    done = [e["tasks_done"] for e in events]
    assert done == sorted(done)
    last = events[-1]
    assert last["phase"] == "PHASE_DONE" and last["eta_seconds"] == 0
    assert last["tasks_done"] == job["tasks_total"]
    assert watch.job["phase"] == "PHASE_DONE"
    status = client.status(job["id"])
    assert status["tasks_done"] == status["tasks_total"] == job["tasks_total"]
    assert any(j["id"] == job["id"] for j in client.jobs())

    out = tmp_path / "fetched.wbk"
    summary = client.fetch(job["id"], str(out))
    assert summary["arrays"] >= 9 and summary["bytes"] > 0
    image = wavebake.relight(str(out), "builtin:sky", terms=64)
    assert image.shape == (16, 16, 3) and np.isfinite(image[wavebake.Store(str(out)).samples["grid"] >= 0]).all()
    with pytest.raises(wavebake.AlreadyExists, match="^out: ") as existing:
        client.fetch(job["id"], out)  # never over an existing path
    assert isinstance(existing.value, FileExistsError) and "--" not in str(existing.value)
    with pytest.raises(wavebake.FailedPrecondition):
        client.cancel(job["id"])  # already DONE


def test_cancel_and_an_early_dropped_watch(coordinator):
    address, token = coordinator
    client = wavebake.Client(address, token_file=token)
    job = client.submit("builtin:sphere-plane", light_res=16, layout="camera:64x64", tile_size=8)
    watch = iter(client.watch(job["id"]))
    first = next(watch)
    assert first["job_id"] == job["id"]
    start = time.time()
    del watch  # stops its stream; must not wait for the job
    assert time.time() - start < 5
    cancelled = client.cancel(job["id"])
    assert cancelled["phase"] == "PHASE_CANCELLED"
    assert [e["phase"] for e in client.watch(job["id"])][-1] == "PHASE_CANCELLED"


def test_errors_are_named(coordinator, tmp_path):
    address, token = coordinator
    with pytest.raises(wavebake.Unauthenticated):
        wavebake.Client(address).jobs()
    client = wavebake.Client(address, token_file=token)
    with pytest.raises(wavebake.InvalidArgument, match="lightres"):
        client.submit("builtin:furnace", lightres=8)
    with pytest.raises(TypeError, match="light_res"):
        client.submit("builtin:furnace", light_res="eight")
    with pytest.raises(wavebake.InvalidArgument, match="light_res"):
        client.submit("builtin:furnace", light_res=33)
    with pytest.raises(wavebake.NotFound):
        client.status(424242)  # an int is a job id too
    with pytest.raises(wavebake.Error, match="missing.obj"):
        client.submit(tmp_path / "missing.obj")
    with pytest.raises(wavebake.Unavailable, match="^coordinator: "):
        wavebake.Client("127.0.0.1:1", connect_seconds=0.2)
