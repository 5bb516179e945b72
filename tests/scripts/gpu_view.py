"""The GPU relight view end to end (run by gpu_view.sh).

Four tiny diffuse stores (camera, uv, hilbert; N = 8, 32x32 cells; and a
camera store at N = 16, whose level-1 nodes carry jump records: the view
runs with --jump-nodes 2, so both the jump and the read-through of a branch
the environment lacks are drawn) are exported and served by `wavebake view`; headless Debian chromium with
SwiftShader (WebGL2, EXT_color_buffer_float, EXT_float_blend) draws each
under a probe, rotation and term count in both modes, and
window.wavebakeGpuFrame() is compared with the server's CPU frame of the
same lights.

mode=tree against /api/view/oracle, the C++ decoder's frame of the same
exported bytes (runtime/gpu/wavelet_tree_reader.h, sharing no code with the
shader). The bound: both decode the same coefficients exactly — a code of
at most 9 bits times a step with a 4-bit mantissa (header "steps") has at
most 13 significant bits, so (code - 2^(b-1))·step is exact in float32 on
the GPU and in the reader — and sum the same float products of them and
the lighting weights; the shader in float32 over at most K = 6·N² terms
per channel (the scaling coefficient and three wavelets per node, six
faces; the walk visits each node pair once), the oracle in double.
Recursive float summation is off by at most K·u·Σ|terms| (u = 2^-24), the
albedo product and the oracle's final rounding add 2·u·Σ|terms|:
|gpu - cpu| <= (K + 2)·u·Σ|terms|, with Σ|terms| (× albedo) returned by the
oracle per cell and channel.

mode=4d against /api/view/oracle4d, the CPU relighter (Relighter::Relight,
Eq. 8) of the same store and lights. Both evaluate
B = Σ_i Σ_k w_i·C_ik·g_k(p) in float32, in different orders: a product
w·C (one rounding), at most K additions into a coefficient's position
(K = the lights, each column adding once per position), two additions per
inverse Haar step (exact halvings) over D ≤ max_depth steps, the albedo
product: n ≤ K + 2D + 2 roundings on any path. Each is within γ_n·M of
the exact sum (Higham §3.1, §4.2), M = Σ |w·C|·|g| the oracle's second
array (runtime/gpu/relight_magnitude.h): |gpu − cpu| ≤ 2·γ_n·M, γ_n =
n·u/(1 − n·u), plus M's own float rounding (one more u).
"""
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import urllib.error
import urllib.request

import numpy as np
import zarr

from browser_lib import SWIFTSHADER_FLAGS, chromium, wait_for

WB = sys.argv[1]
DATA = pathlib.Path(__file__).resolve().parents[2].parent / "shared" / "data"
U = 2.0 ** -24


def run(*args, ok=True):
    p = subprocess.run([WB, *args], capture_output=True, text=True, timeout=300)
    if ok and p.returncode != 0:
        raise SystemExit(f"FAIL: wavebake {' '.join(args)}: {p.stderr}")
    return p


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
    run("export", str(store), "--format", "wavelet-tree", "--out", str(out), "--bits", "9",
        "--cut-off", "0")
    h = json.loads((out / "header.json").read_text())
    assert h["format"] == "wavebake-wavelet-tree/2", h["format"]
    sizes = {"uint8": 1, "uint16": 2, "uint32": 4, "float32": 4}
    for key in ("line", "blocks", "cells"):
        a = h[key]
        want = a["width"] * a["height"] * a["channels"] * sizes[a["type"]]
        got = (out / a["file"]).stat().st_size
        assert got == want, (key, got, want)
    # Cut-off 0 keeps every node: (N²-1)/3 per tree, 9-bit codes at every level.
    n = h["light_res"]
    assert h["stats"]["nodes_kept"] == h["stats"]["trees"] * (n * n - 1) // 3, h["stats"]
    assert h["code_bits"] == [9] * h["levels"] and h["settings"]["bits"] == [9] * h["levels"], h
    grid = zarr.open(str(store), mode="r")["samples/grid"][:].reshape(-1)
    sampled = grid >= 0
    assert h["sampled"] == sampled.sum() and h["stats"]["trees"] == 6 * sampled.sum(), h
    # Cells: A = 1 + the rank of a sampled cell, 0 on masked ones.
    cells = np.fromfile(out / "cells.bin", dtype="<f4").reshape(-1, 4)
    assert (cells[~sampled, 3] == 0).all()
    assert (cells[sampled, 3] == np.arange(1, sampled.sum() + 1)).all()
    # Blocks: every tree present, back to back from unit 0 in block order.
    blocks = np.fromfile(out / "blocks.bin", dtype="<u4").reshape(-1, 2)[: h["blocks"]["texels"]]
    starts = blocks[:, 0].astype(np.int64)
    assert starts[0] == 0 and (np.diff(starts) > 2 * h["levels"]).all(), starts[:8]
    assert starts[-1] < h["line"]["units"] <= 8 * (h["line"]["texels"] - 1), h["line"]
    # Refusals by name: the format, a bad --bits.
    p = run("export", str(store), "--format", "png", "--out", str(tmp / "x"), ok=False)
    assert p.returncode == 2 and "--format" in p.stderr, p.stderr
    for bits in ("12", "8,8", "x"):
        p = run("export", str(store), "--format", "wavelet-tree", "--out", str(tmp / "x"),
                "--bits", bits, ok=False)
        assert p.returncode != 0 and "bits" in p.stderr, (bits, p.stderr)


def main():
    with tempfile.TemporaryDirectory() as d:
        tmp = pathlib.Path(d)
        stores = {
            "camera": ("builtin:disk-over-plane", "camera:32x32", 8),
            "uv": (str(DATA / "models" / "spot.obj"), "uv:32x32", 8),
            "hilbert": (str(tmp / "bump.obj"), "hilbert:32x32", 8),
            "camera16": ("builtin:cubes-wall", "camera:32x32", 16),
        }
        write_bump(tmp / "bump.obj")
        paths = []
        for name, (scene, layout, n) in stores.items():
            path = tmp / f"{name}.wbk"
            run("bake", scene, "--layout", layout, "--light-res", str(n), "--quiet", "--out", str(path))
            paths.append(path)
        check_export(tmp, paths[0])
        vis = tmp / "vis.wbk"
        run("bake", "builtin:sphere-plane", "--layout", "camera:16x16", "--light-res", "8",
            "--transport", "visibility", "--quiet", "--out", str(vis))
        p = run("export", str(vis), "--format", "wavelet-tree", "--out", str(tmp / "v"), ok=False)
        assert p.returncode != 0 and "transport" in p.stderr, p.stderr

        # A LeGall column store: trees yes, mode=4d refused by name.
        legall = tmp / "legall.wbk"
        run("bake", "builtin:disk-over-plane", "--layout", "camera:16x16", "--light-res", "8",
            "--column-filter", "legall53", "--quiet", "--out", str(legall))
        addr = tmp / "addr"
        # The uv store's scene is found by name on WAVEBAKE_SCENE_PATH (its 3D mesh).
        env = dict(os.environ, WAVEBAKE_SCENE_PATH=str(DATA / "models"))
        server = subprocess.Popen([WB, "view", *map(str, paths), str(legall), "--http", "127.0.0.1:0",
                                   "--http-address-file", str(addr), "--jump-nodes", "2"], env=env,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        driver = None
        try:
            wait_for("the view's address", lambda: addr.exists() and addr.read_text().strip(), 120)
            base = "http://" + addr.read_text().strip()
            driver = chromium(tmp / "chromium", SWIFTSHADER_FLAGS, page_load_timeout=60)

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

            def oracle(endpoint, path, q):
                raw = np.frombuffer(get(f"{base}/api/view/{endpoint}?{q}"), dtype="<f4").astype(np.float64)
                grid = zarr.open(str(path), mode="r")["samples/grid"][:]
                h, w = grid.shape
                return grid, raw[: h * w * 3].reshape(h, w, 3), raw[h * w * 3:].reshape(h, w, 3)

            max_depth = {}

            def compare4d(index, path, probe, rotate, terms):
                gpu = frame()
                q = f"store={index}&probe={probe}&rotate={rotate}&terms={terms}"
                grid, cpu, mag = oracle("oracle4d", path, q)
                masked = grid < 0
                assert gpu.shape == cpu.shape, (gpu.shape, cpu.shape)
                assert np.array_equal(np.isnan(gpu).any(axis=2), masked), "GPU mask (4d)"
                assert np.array_equal(np.isnan(cpu).any(axis=2), masked), "CPU mask (4d)"
                if index not in max_depth:
                    max_depth[index] = json.loads(get(f"{base}/api/view/columns/{index}/meta.json"))["max_depth"]
                n = terms + 2 * max_depth[index] + 2
                gamma = n * U / (1 - n * U)
                bound = (2 * gamma + U) * mag[~masked]
                err = np.abs(gpu[~masked] - cpu[~masked])
                assert np.abs(cpu[~masked]).max() > 0, "an all-black frame proves nothing"
                worst = (err - bound).max()
                assert worst <= 0, f"4d store {index} {q}: |gpu-cpu| exceeds the bound by {worst}"
                print(f"4d store {index} ({path.name}) {q}: max |gpu-cpu| {err.max():.3g}, "
                      f"max bound {bound.max():.3g}, max |B| {np.abs(cpu[~masked]).max():.3g}")

            def compare(index, path, probe, rotate, terms):
                gpu = frame()
                q = f"store={index}&probe={probe}&rotate={rotate}&terms={terms}"
                grid, cpu, mag = oracle("oracle", path, q)
                h, w = grid.shape
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
                for rotate, terms in ((0, 64), (45, 16), (200, 1000), (0, 8)):
                    for mode, check in (("tree", compare), ("4d", compare4d)):
                        url = (f"{base}/view?store={i}&probe=builtin:sky&rotate={rotate}"
                               f"&terms={terms}&mode={mode}")
                        status = load(url)
                        assert status == "ready", (url, status)
                        check(i, path, "builtin:sky", rotate, terms)

            # The slider, in both modes: the page redraws from new lighting
            # only (environment trees or kept lights; no pixels, no texture
            # re-download) and still matches.
            last = len(paths) - 1
            for mode, lighting, check in (("tree", "/api/view/env?", compare),
                                          ("4d", "/api/view/lights?", compare4d)):
                status = load(f"{base}/view?store={last}&probe=builtin:sky&rotate=200"
                              f"&terms=1000&mode={mode}")
                assert status == "ready", status
                driver.execute_script("performance.clearResourceTimings();"
                                      "const r = document.getElementById('rotate');"
                                      "r.value = 90; r.dispatchEvent(new Event('input'));")
                wait_for("the slider's frame", lambda: driver.execute_script(
                    "return document.body.dataset.gpuReady === '1' &&"
                    " performance.getEntriesByType('resource').length > 0"))
                urls = driver.execute_script(
                    "return performance.getEntriesByType('resource').map(e => e.name)")
                assert urls and all(lighting in u for u in urls), (mode, urls)
                check(last, paths[-1], "builtin:sky", 90, 1000)

            # The uv store in 3D: the lightmapped mesh drawn (a mesh only for
            # uv), and turning the camera redraws with no request.
            listed = json.loads(get(f"{base}/api/view/stores"))
            assert [s["mesh"] for s in listed] == [False, True, False, False, False], listed
            try:
                get(f"{base}/api/view/columns/4/meta.json")
                raise AssertionError("a LeGall store's columns were served")
            except urllib.error.HTTPError as e:
                body = e.read().decode()
                assert e.code == 409 and "column_filter" in body, (e.code, body)
            trees16 = json.loads(get(f"{base}/api/view/trees/3/header.json"))
            assert trees16["levels"] == 4 and trees16["stats"]["jumps"] > 0, trees16["stats"]
            assert json.loads(get(f"{base}/api/view/trees/4/header.json"))["format"]
            status = load(f"{base}/view?store=4&mode=4d")
            assert status.startswith("error: ") and "column_filter" in status, status
            status = load(f"{base}/view?store=1&probe=builtin:sky&terms=64&mode=4d")
            assert status == "ready", status
            assert driver.execute_script("return document.body.dataset.view3d;") == "1"
            shown = ("const c = document.getElementById('view'); const gl = c.getContext('webgl2');"
                     "const p = new Uint8Array(c.width * c.height * 4);"
                     "gl.bindFramebuffer(gl.FRAMEBUFFER, null);"
                     "gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, p);"
                     "return Array.from(p);")
            before = np.array(driver.execute_script(shown)).reshape(-1, 4)
            background = np.all(np.abs(before[:, :3] - before[0, :3]) <= 2, axis=1)
            assert 0.05 < 1 - background.mean() < 0.95, f"mesh covers {1 - background.mean():.2f} of the view"
            driver.execute_script("performance.clearResourceTimings(); window.wavebakeOrbit(1.2, 0.3);")
            after = np.array(driver.execute_script(shown)).reshape(-1, 4)
            changed = np.any(np.abs(after.astype(int) - before) > 8, axis=1).mean()
            assert changed > 0.05, f"the orbit changed {changed:.3f} of the pixels"
            assert driver.execute_script("return performance.getEntriesByType('resource').length;") == 0
            compare4d(1, paths[1], "builtin:sky", 0, 64)
            print(f"uv store in 3D: mesh on {1 - background.mean():.2f} of the view, orbit changed "
                  f"{changed:.2f}, no request")

            status = load(f"{base}/view?store=0&mode=3d")
            assert status.startswith("error: mode 3d"), status
        finally:
            if driver:
                driver.quit()
            server.terminate()
            server.wait(timeout=30)
        print("ok")


if __name__ == "__main__":
    main()
