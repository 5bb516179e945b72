#!/usr/bin/python3
"""Relighting on the GPU against the CPU relighter, on one store and one
lighting (run by bench/gpu_modes.sh; the numbers of chart 11 in
docs/RESULTS.md).

    /usr/bin/python3 bench/gpu_modes.py WAVEBAKE STORE [--probes DIR]
        [--probe NAME] [--terms K] [--frames F] [--cut-off C]... [--jump-nodes J]
        [--real-gpu] [--eval-json FILE] [--csv OUT]

For each tree cut-off ("default": the export's default setting) it serves
the store with `wavebake view --cut-off C`, loads /view?mode=tree and, once,
/view?mode=4d in headless Debian chromium, and asks the page for
window.wavebakeGpuBench(F): F frames of the same lighting, each waited for,
the lighting's download excluded. The CPU relighter (Relighter::Relight,
Eq. 8, one core) relights the same store under the same lights: the
median of the X-Frame-Ms of F frames of /api/view/oracle4d. Printed per
mode: the device, ms and frames/s, the per-pixel work (tree: transfer records read
per sampled cell, read from the shader's own count; 4d and CPU:
coefficients scattered per grid cell, plus the inverse steps' full-frame
passes), bytes on the GPU, and frames/s against the CPU relighter's.

--jump-nodes J serves every tree setting with `wavebake view --jump-nodes J`
(default: the export's). --real-gpu drops the SwiftShader flags (ANGLE picks the machine's GPU);
--eval-json adds each setting's error against the reference from
`wavebake eval STORE --env ENV --tree-cut-off ... --json`.
"""
import argparse
import csv
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request

from selenium import webdriver
from selenium.webdriver.chrome.service import Service

SWIFTSHADER = ["--use-angle=swiftshader", "--enable-unsafe-swiftshader"]
REAL_GPU = ["--enable-gpu", "--ignore-gpu-blocklist", "--use-angle=default"]


def wait_for(what, predicate, timeout):
    end = time.time() + timeout
    while time.time() < end:
        v = predicate()
        if v:
            return v
        time.sleep(0.05)
    raise SystemExit(f"timed out waiting for {what}")


def browser(tmp, real_gpu):
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for flag in ["--headless", "--no-sandbox", "--disable-gpu-sandbox", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update",
                 "--disable-sync", "--disable-dev-shm-usage", f"--user-data-dir={tmp}"] + (
                     REAL_GPU if real_gpu else SWIFTSHADER):
        options.add_argument(flag)
    d = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    d.set_page_load_timeout(120)
    d.set_script_timeout(600)
    return d


class View:
    """`wavebake view STORE` with one tree setting, for the length of a with."""

    def __init__(self, wb, store, cut_off, probes, tmp, jump_nodes=None):
        self.addr = pathlib.Path(tmp) / f"addr-{cut_off}"
        args = [wb, "view", str(store), "--http", "127.0.0.1:0", "--http-address-file",
                str(self.addr)]
        if cut_off != "default":
            args += ["--cut-off", str(cut_off)]
        if probes:
            args += ["--probes", probes]
        if jump_nodes:
            args += ["--jump-nodes", str(jump_nodes)]
        self.p = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)

    def __enter__(self):
        wait_for("the view's address", lambda: self.p.poll() is not None or (
            self.addr.exists() and self.addr.read_text().strip()), 600)
        if self.p.poll() is not None:
            raise SystemExit(f"wavebake view failed: {self.p.stderr.read()}")
        self.base = "http://" + self.addr.read_text().strip()
        return self

    def __exit__(self, *exc):
        self.p.terminate()
        self.p.wait(timeout=30)


def gpu_bench(driver, base, q, mode, frames):
    driver.get(f"{base}/view?{q}&mode={mode}")
    status = wait_for("the first frame", lambda: driver.execute_script(
        "return document.body.dataset.gpuError ? 'error: ' + document.body.dataset.gpuError"
        " : (document.body.dataset.gpuReady === '1' ? 'ready' : '')"), 600)
    if status != "ready":
        raise SystemExit(f"mode={mode}: {status}")
    return driver.execute_script(f"return window.wavebakeGpuBench({frames});")


def cpu_bench(base, q, frames):
    ms, coefficients = [], 0
    for _ in range(frames):
        with urllib.request.urlopen(f"{base}/api/view/oracle4d?{q}", timeout=120) as r:
            ms.append(float(r.headers["X-Frame-Ms"]))
            coefficients = int(r.headers["X-Coefficients"])
            r.read()
    return statistics.median(ms), coefficients


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("wavebake")
    ap.add_argument("store")
    ap.add_argument("--probes", default="")
    ap.add_argument("--probe", default="builtin:sky")
    ap.add_argument("--terms", type=int, default=256)
    ap.add_argument("--frames", type=int, default=20)
    ap.add_argument("--cut-off", action="append", dest="cut_offs")
    ap.add_argument("--jump-nodes", type=int, default=0)
    ap.add_argument("--real-gpu", action="store_true")
    ap.add_argument("--eval-json", default="")
    ap.add_argument("--csv", default="")
    a = ap.parse_args()
    cut_offs = a.cut_offs or ["default"]
    errors = {}
    if a.eval_json:
        e = json.loads(pathlib.Path(a.eval_json).read_text())
        errors["store"] = e["compressed"]["rel_rms"]
        for row in e["trees"]:
            errors[("default" if row["target_error"] is not None else f"{row['cut_off']:g}")] = row
    q = f"store=0&probe={a.probe}&rotate=0&terms={a.terms}"
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        driver = browser(pathlib.Path(tmp) / "chromium", a.real_gpu)
        try:
            for i, c in enumerate(cut_offs):
                with View(a.wavebake, a.store, c, a.probes, tmp, a.jump_nodes) as v:
                    stores = json.loads(urllib.request.urlopen(f"{v.base}/api/view/stores").read())
                    s = stores[0]
                    if i == 0:
                        meta = json.loads(urllib.request.urlopen(
                            f"{v.base}/api/view/columns/0/meta.json").read())
                        cpu_ms, coefficients = cpu_bench(v.base, q, a.frames)
                        d4 = gpu_bench(driver, v.base, q, "4d", a.frames)
                        cells = s["width"] * s["height"]
                        rows.append({"mode": "cpu relighter", "cut_off": "", "device": "CPU, one core",
                                     "ms": cpu_ms, "work": coefficients / cells,
                                     "unit": "coefficients added", "passes": d4["work"]["passes"],
                                     "bytes": meta["bytes"], "error": errors.get("store")})
                        rows.append({"mode": "gpu 4d", "cut_off": "", "device": d4["device"],
                                     "ms": d4["msPerFrame"], "work": d4["work"]["perPixel"],
                                     "unit": d4["work"]["unit"], "passes": d4["work"]["passes"],
                                     "bytes": d4["bytesOnGpu"], "error": errors.get("store")})
                    t = gpu_bench(driver, v.base, q, "tree", a.frames)
                    e = errors.get(c if c == "default" else f"{float(c):g}")
                    rows.append({"mode": "gpu tree", "cut_off": c, "device": t["device"],
                                 "ms": t["msPerFrame"], "work": t["work"]["perPixel"],
                                 "unit": t["work"]["unit"], "passes": 1, "bytes": t["bytesOnGpu"],
                                 "error": e["rel_rms"] if e else None,
                                 "actual_cut_off": e["cut_off"] if e else None})
        finally:
            driver.quit()
    cpu_fps = 1000 / rows[0]["ms"]
    print(f"store {a.store}: {s['width']}x{s['height']}, N = {s['light_res']}; probe {a.probe}, "
          f"{a.terms} terms; {a.frames} frames each")
    print(f"device: {rows[1]['device']}")
    print(f"{'mode':14} {'cut-off':>9} {'MB on GPU':>10} {'ms/frame':>9} {'frames/s':>9} "
          f"{'vs CPU':>7} {'work per pixel':>34} {'rel_rms':>8}")
    for r in rows:
        fps = 1000 / r["ms"]
        err = f"{r['error']:.4f}" if r["error"] is not None else "-"
        print(f"{r['mode']:14} {str(r['cut_off']):>9} {r['bytes'] / 1e6:10.2f} {r['ms']:9.2f} "
              f"{fps:9.1f} {fps / cpu_fps:7.3g} {r['work']:12.2f} {r['unit']:>18}"
              f" +{r['passes']} {err:>8}")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=["mode", "cut_off", "actual_cut_off", "device", "ms",
                                              "work", "unit", "passes", "bytes", "error"])
            w.writeheader()
            for r in rows:
                w.writerow({k: r.get(k, "") for k in w.fieldnames})


if __name__ == "__main__":
    sys.exit(main())
