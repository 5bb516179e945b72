"""The GPU relight view end to end (run by gpu_view.sh).

Three tiny diffuse stores (camera, uv, hilbert; N = 8, 32x32 cells) are
exported and served by `wavebake view`; headless Debian chromium with
SwiftShader (WebGL2, EXT_color_buffer_float) draws each under a probe,
rotation and term count, and window.wavebakeGpuFrame() is compared with
/api/view/oracle, the C++ decoder's frame of the same exported bytes
(runtime/wavelet_tree_reader.h, sharing no code with the shader).

The bound: both sum the same float products of the same decoded
coefficients and lighting weights; the shader in float32 over at most
K = 6·N² terms per channel (the scaling coefficient and three wavelets per
node, six faces), the oracle in double. Recursive float summation is off by
at most K·u·Σ|terms| (u = 2^-24), the albedo product and the oracle's final
rounding add 2·u·Σ|terms|: |gpu - cpu| <= (K + 2)·u·Σ|terms|, with Σ|terms|
(× albedo) returned by the oracle per cell and channel.
"""
import json
import pathlib
import subprocess
import sys
import tempfile
import time
import urllib.request

import numpy as np
import zarr
from selenium import webdriver
from selenium.webdriver.chrome.service import Service

WB = sys.argv[1]
DATA = pathlib.Path(__file__).resolve().parents[2].parent / "shared" / "data"
U = 2.0 ** -24


def run(*args, ok=True):
    p = subprocess.run([WB, *args], capture_output=True, text=True, timeout=300)
    if ok and p.returncode != 0:
        raise SystemExit(f"FAIL: wavebake {' '.join(args)}: {p.stderr}")
    return p


def wait_for(what, predicate, timeout=60):
    end = time.time() + timeout
    while time.time() < end:
        v = predicate()
        if v:
            return v
        time.sleep(0.05)
    raise SystemExit(f"FAIL: timed out waiting for {what}")


def get(url):
    with urllib.request.urlopen(url, timeout=30) as r:
        return r.read()


def write_bump(path, n=24):
    """A height field of n x n vertices (fewer than the 1024 cells of
    hilbert:32x32, so some cells stay masked) with a bump that shadows."""
    lines = []
    for j in range(n):
        for i in range(n):
            x, y = 2 * i / (n - 1) - 1, 2 * j / (n - 1) - 1
            lines.append(f"v {x} {0.6 * np.exp(-8 * (x * x + y * y)):.6f} {y}")
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i + 1
            lines += [f"f {a} {a + n} {a + 1}", f"f {a + 1} {a + n} {a + n + 1}"]
    path.write_text("\n".join(lines) + "\n")


def check_export(tmp, store):
    out = tmp / "trees"
    run("export", str(store), "--format", "wavelet-tree", "--out", str(out), "--bits", "16",
        "--cut-off", "0")
    h = json.loads((out / "header.json").read_text())
    assert h["format"] == "wavebake-wavelet-tree/1", h["format"]
    sizes = {"uint8": 1, "uint16": 2, "uint32": 4, "float32": 4}
    for key in ("line", "blocks", "cells"):
        a = h[key]
        want = a["width"] * a["height"] * a["channels"] * sizes[a["type"]]
        got = (out / a["file"]).stat().st_size
        assert got == want, (key, got, want)
    # Cut-off 0 keeps every node: (N²-1)/3 per tree.
    n = h["light_res"]
    assert h["stats"]["nodes_kept"] == h["stats"]["trees"] * (n * n - 1) // 3, h["stats"]
    blocks = np.fromfile(out / "blocks.bin", dtype="<u4").reshape(-1, 4)[: h["blocks"]["texels"]]
    grid = zarr.open(str(store), mode="r")["samples/grid"][:]
    sampled = np.repeat(grid.reshape(-1) >= 0, 6)
    assert (blocks[sampled, 1] > 0).all() and (blocks[~sampled, 1] == 0).all()
    assert blocks[:, 0].max() + 0 <= h["line"]["texels"]
    # Refusals by name: the format, a bad --bits.
    p = run("export", str(store), "--format", "png", "--out", str(tmp / "x"), ok=False)
    assert p.returncode == 2 and "--format" in p.stderr, p.stderr
    p = run("export", str(store), "--format", "wavelet-tree", "--out", str(tmp / "x"),
            "--bits", "12", ok=False)
    assert p.returncode != 0 and "bits" in p.stderr, p.stderr


def main():
    with tempfile.TemporaryDirectory() as d:
        tmp = pathlib.Path(d)
        stores = {
            "camera": ("builtin:disk-over-plane", "camera:32x32"),
            "uv": (str(DATA / "models" / "spot.obj"), "uv:32x32"),
            "hilbert": (str(tmp / "bump.obj"), "hilbert:32x32"),
        }
        write_bump(tmp / "bump.obj")
        paths = []
        for name, (scene, layout) in stores.items():
            path = tmp / f"{name}.wbk"
            run("bake", scene, "--layout", layout, "--light-res", "8", "--quiet", "--out", str(path))
            paths.append(path)
        check_export(tmp, paths[0])
        vis = tmp / "vis.wbk"
        run("bake", "builtin:sphere-plane", "--layout", "camera:16x16", "--light-res", "8",
            "--transport", "visibility", "--quiet", "--out", str(vis))
        p = run("export", str(vis), "--format", "wavelet-tree", "--out", str(tmp / "v"), ok=False)
        assert p.returncode != 0 and "transport" in p.stderr, p.stderr

        addr = tmp / "addr"
        server = subprocess.Popen([WB, "view", *map(str, paths), "--http", "127.0.0.1:0",
                                   "--http-address-file", str(addr)],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        driver = None
        try:
            wait_for("the view's address", lambda: addr.exists() and addr.read_text().strip(), 120)
            base = "http://" + addr.read_text().strip()
            options = webdriver.ChromeOptions()
            options.binary_location = "/usr/bin/chromium"
            for flag in ("--headless", "--no-sandbox", "--use-angle=swiftshader",
                         "--enable-unsafe-swiftshader", "--disable-gpu-sandbox",
                         "--disable-background-networking", "--disable-component-update",
                         "--disable-sync", "--no-first-run", "--disable-dev-shm-usage",
                         f"--user-data-dir={tmp / 'chromium'}"):
                options.add_argument(flag)
            driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
            driver.set_page_load_timeout(60)

            def load(url):
                driver.get(url)
                return wait_for(url, lambda: driver.execute_script(
                    "return document.body.dataset.gpuError ? 'error: ' + document.body.dataset.gpuError"
                    " : (document.body.dataset.gpuReady === '1' ? 'ready' : '')"), 120)

            def frame():
                f = driver.execute_script(
                    "const f = window.wavebakeGpuFrame();"
                    "return {width: f.width, height: f.height, isF32: f.data instanceof Float32Array,"
                    " data: Array.from(f.data, v => Number.isNaN(v) ? null : v)};")
                assert f["isF32"]
                data = np.array([np.nan if v is None else v for v in f["data"]], dtype=np.float64)
                return data.reshape(f["height"], f["width"], 3)

            def compare(index, path, probe, rotate, terms):
                gpu = frame()
                q = f"store={index}&probe={probe}&rotate={rotate}&terms={terms}"
                raw = np.frombuffer(get(f"{base}/api/view/oracle?{q}"), dtype="<f4").astype(np.float64)
                grid = zarr.open(str(path), mode="r")["samples/grid"][:]
                h, w = grid.shape
                cpu, mag = raw[: h * w * 3].reshape(h, w, 3), raw[h * w * 3:].reshape(h, w, 3)
                assert gpu.shape == (h, w, 3), (gpu.shape, grid.shape)
                masked = grid < 0
                assert np.array_equal(np.isnan(gpu).any(axis=2), masked), "GPU mask"
                assert np.array_equal(np.isnan(cpu).any(axis=2), masked), "CPU mask"
                n = json.loads(get(f"{base}/api/view/stores"))[index]["light_res"]
                bound = (6 * n * n + 2) * U * mag[~masked]
                err = np.abs(gpu[~masked] - cpu[~masked])
                assert np.abs(cpu[~masked]).max() > 0, "an all-black frame proves nothing"
                worst = (err - bound).max()
                assert worst <= 0, f"store {index} {q}: |gpu-cpu| exceeds the bound by {worst}"
                print(f"store {index} ({path.name}) {q}: max |gpu-cpu| {err.max():.3g}, "
                      f"max bound {bound.max():.3g}, max |B| {np.abs(cpu[~masked]).max():.3g}")

            status = load(f"{base}/view?store=0&mode=tree")
            assert status == "ready", status
            assert driver.execute_script(
                "const gl = document.createElement('canvas').getContext('webgl2');"
                "return !!gl && !!gl.getExtension('EXT_color_buffer_float');")
            for i, path in enumerate(paths):
                for rotate, terms in ((0, 64), (45, 16), (200, 1000)):
                    url = (f"{base}/view?store={i}&probe=builtin:sky&rotate={rotate}"
                           f"&terms={terms}&mode=tree")
                    status = load(url)
                    assert status == "ready", (url, status)
                    compare(i, path, "builtin:sky", rotate, terms)

            # The slider: the page redraws from new environment trees only
            # (no pixels, no texture re-download) and still matches.
            driver.execute_script("performance.clearResourceTimings();"
                                  "const r = document.getElementById('rotate');"
                                  "r.value = 90; r.dispatchEvent(new Event('input'));")
            wait_for("the slider's frame", lambda: driver.execute_script(
                "return document.body.dataset.gpuReady === '1' &&"
                " performance.getEntriesByType('resource').length > 0"))
            urls = driver.execute_script(
                "return performance.getEntriesByType('resource').map(e => e.name)")
            assert urls and all("/api/view/env?" in u for u in urls), urls
            compare(len(paths) - 1, paths[-1], "builtin:sky", 90, 1000)

            status = load(f"{base}/view?store=0&mode=4d")
            assert status.startswith("error: mode 4d"), status
        finally:
            if driver:
                driver.quit()
            server.terminate()
            server.wait(timeout=30)
        print("ok")


if __name__ == "__main__":
    main()
