"""wavebake.Client against a real coordinator and worker (conftest): submit,
watch as an iterator of events to the end, status, fetch a verified store
and relight it, cancel; errors named; one JSON shape of a job from Python,
`wavebake status --json` and the web monitor's /api/jobs."""
import json
import os
import subprocess
import time
import urllib.request

import numpy as np
import pytest

import wavebake

PARAMS = dict(light_res=8, layout="camera:16x16", tile_size=8, column_group=128)


def test_submit_watch_fetch_relight(coordinator, tmp_path):
    address, token = coordinator
    client = wavebake.Client(address, token_file=token)
    job = client.submit("builtin:cubes-wall", **PARAMS)
    assert job["phase"] in ("QUEUED", "BAKING")
    assert job["request"]["light_res"] == 8
    watch = client.watch(job["id"])
    events = list(watch)
    assert events, "no events"
    seqs = [e["seq"] for e in events if e["kind"] != "PROGRESS"]
    assert seqs == sorted(seqs) and len(seqs) == len(set(seqs))
    done = [e["tasks_done"] for e in events]
    assert done == sorted(done)
    last = events[-1]
    assert last["phase"] == "DONE" and last["eta_seconds"] == 0
    assert last["tasks_done"] == job["tasks_total"]
    assert watch.job["phase"] == "DONE"
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
    assert cancelled["phase"] == "CANCELLED"
    assert [e["phase"] for e in client.watch(job["id"])][-1] == "CANCELLED"


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


def test_one_job_shape_everywhere(coordinator):
    """The same finished job read three ways is the same JSON: the Job message
    with phases spelled DONE and every number a number."""
    address, token = coordinator
    client = wavebake.Client(address, token_file=token)
    job = client.submit("builtin:furnace", **PARAMS)
    for _ in client.watch(job["id"]):
        pass
    ours = client.status(job["id"])
    cli = subprocess.run([os.environ["WB_WAVEBAKE_BIN"], "status", job["id"], "--json",
                          "--coordinator", address, "--token-file", token],
                         capture_output=True, text=True, check=True)
    theirs = json.loads(cli.stdout)
    token_text = open(token).read().strip()
    request = urllib.request.Request(f"http://{coordinator.http}/api/jobs/{job['id']}",
                                     headers={"Authorization": f"Bearer {token_text}"})
    with urllib.request.urlopen(request, timeout=10) as response:
        web = json.loads(response.read())
    with urllib.request.urlopen(urllib.request.Request(
            f"http://{coordinator.http}/api/jobs", headers=request.headers), timeout=10) as response:
        listed = [j for j in json.loads(response.read()) if j["id"] == job["id"]]
    assert ours == theirs == web == listed[0]
    assert ours["phase"] == "DONE"
    assert isinstance(ours["rays_traced"], int) and ours["rays_traced"] > 0
    assert isinstance(ours["created_ms"], int) and isinstance(ours["request"]["light_res"], int)
    assert set(ours) >= {"id", "request", "phase", "tasks_done", "tasks_total", "rays_estimate",
                         "rays_per_second", "eta_seconds", "stats_json", "finished_ms"}
