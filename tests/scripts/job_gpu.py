"""The job page's GPU relight path end to end (run by job_gpu.sh).

A coordinator (token, --http) and one worker bake a tiny camera store; headless
Debian chromium with SwiftShader (WebGL2, EXT_color_buffer_float,
EXT_float_blend) opens the job page, which must draw on the GPU (the
relight-gpu canvas, data-gpu="1"), not ask the server for frames. The test
then turns the rotation slider and the term count and counts the requests
the page made: only /api/jobs/ID/gpu/lights, none to /api/jobs/ID/relight,
and the drawn pixels change. A visibility store's page falls back to the
server's frames (its GPU arrays are refused by name). Every process it starts
is stopped by its pid; every wait is bounded.
"""
import json
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from pathlib import Path

from selenium.webdriver.common.by import By

from browser_lib import SWIFTSHADER_FLAGS, chromium, stop, wait_for

WB = sys.argv[1]
TOKEN = "gpu-test-token"


def cli(*args):
    return subprocess.run([WB, *args], check=True, capture_output=True, text=True, timeout=120).stdout


def main():
    with tempfile.TemporaryDirectory(prefix="wb_jobgpu_") as d:
        tmp = Path(d)
        procs, driver = [], None
        try:
            token = tmp / "token"
            token.write_text(TOKEN + "\n")
            grpc_file, http_file = tmp / "grpc", tmp / "http"
            procs.append(subprocess.Popen(
                [WB, "coordinator", "--listen", "127.0.0.1:0", "--data", str(tmp / "data"),
                 "--token-file", str(token), "--address-file", str(grpc_file), "--http", "127.0.0.1:0",
                 "--http-address-file", str(http_file), "--lease-wait-ms", "50"],
                stderr=open(tmp / "coordinator.log", "w")))
            wait_for("the coordinator", lambda: grpc_file.exists() and http_file.exists(), 30)
            grpc, base = grpc_file.read_text().strip(), "http://" + http_file.read_text().strip()
            procs.append(subprocess.Popen(
                [WB, "worker", "--coordinator", grpc, "--store-root", str(tmp / "data" / "store"),
                 "--token-file", str(token), "--threads", "2"], stderr=open(tmp / "worker.log", "w")))
            client = ["--coordinator", grpc, "--token-file", str(token)]
            diffuse = cli("submit", "builtin:sphere-plane", "--light-res", "8", "--layout", "camera:32x32",
                          *client).strip()
            visibility = cli("submit", "builtin:sphere-plane", "--light-res", "8", "--layout", "camera:16x16",
                             "--transport", "visibility", *client).strip()
            for job in (diffuse, visibility):
                wait_for(f"job {job} DONE", lambda: json.loads(cli("status", job, "--json", *client))["phase"]
                         == "DONE", 120, 0.25)

            # The refusal by name, through the API.
            req = urllib.request.Request(f"{base}/api/jobs/{visibility}/gpu/meta.json",
                                         headers={"Authorization": f"Bearer {TOKEN}"})
            try:
                urllib.request.urlopen(req, timeout=10)
                raise AssertionError("a visibility store's GPU arrays were served")
            except urllib.error.HTTPError as e:
                body = e.read().decode()
                assert e.code == 409 and "transport" in body, (e.code, body)

            driver = chromium(tmp / "chromium", SWIFTSHADER_FLAGS)
            driver.get(base + "/")
            driver.find_element(By.ID, "token").send_keys(TOKEN)
            driver.find_element(By.ID, "signin").click()
            time.sleep(0.2)

            driver.get(f"{base}/jobs/{diffuse}")
            wait_for("a GPU frame", lambda: driver.execute_script(
                "return (window.wavebakeFrames || 0) >= 1 &&"
                " document.getElementById('relight-gpu').dataset.gpu === '1';"), 60)
            assert driver.execute_script("return document.getElementById('relight').hidden;")
            pixels = ("const c = document.getElementById('relight-gpu');"
                      "const gl = c.getContext('webgl2'); const p = new Uint8Array(c.width * c.height * 4);"
                      "gl.bindFramebuffer(gl.FRAMEBUFFER, null);"
                      "gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, p); return Array.from(p);")
            before = driver.execute_script(pixels)
            assert max(before) > 0, "an all-black frame proves nothing"
            driver.execute_script("performance.clearResourceTimings();")
            frames = driver.execute_script("return window.wavebakeFrames;")
            for value in (30, 60, 90):  # the slider moving, one input event a step
                driver.execute_script(
                    f"const r = document.getElementById('rotate'); r.value = {value};"
                    " r.dispatchEvent(new Event('input'));")
            driver.execute_script(
                "const t = document.getElementById('terms'); t.value = Number(t.value) - 2;"
                " t.dispatchEvent(new Event('input'));")
            wait_for("the last setting drawn", lambda: "rotate=90&" in (driver.execute_script(
                "return document.getElementById('relight-gpu').dataset.query || '';")), 30)
            time.sleep(0.3)  # anything still to come would show now
            urls = driver.execute_script("return performance.getEntriesByType('resource').map(e => e.name);")
            frame_requests = [u for u in urls if f"/api/jobs/{diffuse}/relight" in u]
            lights = [u for u in urls if f"/api/jobs/{diffuse}/gpu/lights?" in u]
            assert not frame_requests, frame_requests
            assert lights and len(lights) == len(urls), urls
            after = driver.execute_script(pixels)
            differing = sum(1 for a, b in zip(before, after) if abs(a - b) > 8)
            assert differing > 100, f"only {differing} channel values changed"
            drawn = driver.execute_script("return window.wavebakeFrames;") - frames
            stats = driver.find_element(By.ID, "relight-stats").text
            assert stats.startswith("GPU ("), stats
            print(f"slider and terms: {drawn} GPU frames, {len(lights)} lighting requests, "
                  f"0 frame requests, {differing} channel values changed; {stats}")

            # The visibility store: the server's frames.
            driver.get(f"{base}/jobs/{visibility}")
            wait_for("a server frame", lambda: driver.execute_script(
                "return (document.getElementById('relight').dataset.query || '') !== '';"), 60)
            assert driver.execute_script("return document.getElementById('relight-gpu').hidden;")
            print("visibility store: server frames")
        finally:
            stop(driver, procs)
    print("ok")


if __name__ == "__main__":
    main()
