"""Fixtures of the Python module's tests: stores baked once per session with
wavebake.bake (the embedded bake), and a coordinator with a worker started
and stopped around the client tests."""
import os
import subprocess
import time
from pathlib import Path

import pytest

import wavebake

BIN = os.environ.get("WB_WAVEBAKE_BIN", "")
SMALL = dict(light_res=8, tile_size=8, column_group=128)


@pytest.fixture(scope="session")
def stores(tmp_path_factory):
    """builtin:furnace and builtin:cubes-wall, camera 16x16, N = 8."""
    root = tmp_path_factory.mktemp("stores")
    out = {}
    for name in ("furnace", "cubes-wall"):
        path = root / f"{name}.wbk"
        job = wavebake.bake(f"builtin:{name}", str(path), workers=2, layout="camera:16x16", **SMALL)
        assert job["phase"] == "DONE", job
        out[name] = path
    return out


class Cluster(tuple):
    """(address, token file); .http: the coordinator's web monitor (host:port)."""


@pytest.fixture(scope="session")
def coordinator(tmp_path_factory):
    """A coordinator (with a token and its web monitor) and one worker;
    yields a Cluster (address, token file)."""
    assert BIN, "WB_WAVEBAKE_BIN names the wavebake binary"
    root = tmp_path_factory.mktemp("cluster")
    token = root / "token"
    token.write_text("python-test-token\n")
    address_file = root / "address"
    procs = [subprocess.Popen([BIN, "coordinator", "--listen", "127.0.0.1:0", "--data", str(root / "data"),
                               "--token-file", str(token), "--address-file", str(address_file),
                              "--http", "127.0.0.1:0", "--http-address-file", str(root / "http")],
                              stderr=subprocess.DEVNULL)]
    try:
        deadline = time.time() + 30
        while not (address_file.exists() and (root / "http").exists()):
            assert time.time() < deadline, "coordinator did not start"
            assert procs[0].poll() is None, "coordinator exited"
            time.sleep(0.05)
        address = address_file.read_text().strip()
        procs.append(subprocess.Popen([BIN, "worker", "--coordinator", address, "--store-root",
                                       str(root / "data" / "store"), "--token-file", str(token),
                                       "--threads", "2"], stderr=subprocess.DEVNULL))
        cluster = Cluster((address, str(token)))
        cluster.http = (root / "http").read_text().strip()
        yield cluster
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
