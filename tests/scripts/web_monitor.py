"""Browser test of the web monitor (run by web_monitor.sh with the binary).

Starts a coordinator (token, --http on a free port, --probes) and one worker
thread, submits a bake slow enough to watch and a second one to cancel, then
drives headless chromium: the login form, progress advancing on the jobs page
without a reload, cancel, the job page's relight view answering the rotation
slider with a different image (server frames: WebGL is off, the fallback),
screenshots under the build directory. Checks
401 without the token and that /metrics parses (prometheus_client's parser)
with task counters equal to `wavebake status --json`, per-job series only
for live jobs, and (when Debian's prometheus package is installed) that
`promtool check metrics` accepts it. Every process it starts
is stopped by its pid; every wait is bounded.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from pathlib import Path

from prometheus_client.parser import text_string_to_metric_families
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.support.ui import Select

from browser_lib import chromium, stop, wait_for

WB = sys.argv[1]
BUILD = Path(os.environ.get("WB_BINARY_DIR", Path(WB).parent))
SHOTS = BUILD / "web_screenshots"
PROBES = Path(os.environ.get("WB_SHARED_DATA", "")) / "probes"
TOKEN = "browser-test-token"


def http(url, token=None):
    request = urllib.request.Request(url)
    if token:
        request.add_header("Authorization", f"Bearer {token}")
    try:
        with urllib.request.urlopen(request, timeout=10) as r:
            return r.status, r.read().decode()
    except urllib.error.HTTPError as e:
        return e.code, e.read().decode()


def cli(*args):
    return subprocess.run([WB, *args], check=True, capture_output=True, text=True).stdout


def main():
    SHOTS.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix="wb_web_", dir=BUILD / "test_tmp" if (BUILD / "test_tmp").is_dir() else None))
    procs, driver = [], None
    try:
        token = tmp / "token"
        token.write_text(TOKEN + "\n")
        grpc_file, http_file = tmp / "grpc", tmp / "http"
        log = open(tmp / "coordinator.log", "w")
        procs.append(subprocess.Popen(
            [WB, "coordinator", "--listen", "127.0.0.1:0", "--data", str(tmp / "data"), "--token-file", str(token),
             "--address-file", str(grpc_file), "--http", "127.0.0.1:0", "--http-address-file", str(http_file),
             "--probes", str(PROBES), "--lease-wait-ms", "50"], stderr=log))
        wait_for("the coordinator", lambda: grpc_file.exists() and http_file.exists(), 30)
        grpc, base = grpc_file.read_text().strip(), "http://" + http_file.read_text().strip()
        procs.append(subprocess.Popen(
            [WB, "worker", "--coordinator", grpc, "--store-root", str(tmp / "data" / "store"),
             "--token-file", str(token), "--threads", "1"], stderr=open(tmp / "worker.log", "w")))
        client = ["--coordinator", grpc, "--token-file", str(token)]

        # No token, no monitor (but the health probe).
        for path in ("/", "/metrics", "/api/jobs", "/jobs/1"):
            status, _ = http(base + path)
            assert status == 401, (path, status)
        assert http(base + "/healthz") == (200, "ok\n")

        # Brute force (refinement would finish it before the page could watch it advance).
        slow = cli("submit", "builtin:cubes-wall", "--light-res", "32", "--layout", "camera:64x64",
                   "--tile-size", "16", "--refine", "off", "--supersample", "16", *client).strip()
        queued = cli("submit", "builtin:sphere-plane", "--light-res", "8", "--layout", "camera:16x16", *client).strip()

        # No WebGL: the relight view falls back to the server's frames, which
        # this test watches (tests/scripts/job_gpu.py drives the GPU path).
        driver = chromium(tmp / "chromium", ("--disable-gpu", "--disable-webgl", "--disable-quic",
                                             "--window-size=1280,760"))

        # The login form a browser gets with its 401.
        driver.get(base + "/")
        driver.find_element(By.ID, "token").send_keys(TOKEN)
        driver.find_element(By.ID, "signin").click()
        wait_for("the jobs table", lambda: driver.find_elements(By.ID, f"job-{slow}"), 20)
        driver.execute_script("window.__sameDocument = 42;")

        def tasks_done(job):
            text = driver.find_element(By.CSS_SELECTOR, f"#job-{job} td.tasks").text
            return int(text.split("/")[0]) if "/" in text else -1

        first = wait_for("the slow job's first task", lambda: tasks_done(slow) > 0 and tasks_done(slow), 60)
        later = wait_for("progress on screen", lambda: tasks_done(slow) > first and tasks_done(slow), 60)
        assert driver.execute_script("return window.__sameDocument;") == 42, "the page reloaded"
        driver.save_screenshot(str(SHOTS / "monitor.png"))
        print(f"progress advanced on screen without a reload: {first} -> {later} tasks")

        # Cancel the queued job from the page.
        driver.find_element(By.CSS_SELECTOR, f"#job-{queued} button.cancel").click()
        wait_for("CANCELLED on screen",
                 lambda: driver.find_element(By.CSS_SELECTOR, f"#job-{queued} td.phase").text == "CANCELLED", 20)
        assert json.loads(cli("status", queued, "--json", *client))["phase"] == "CANCELLED"

        wait_for("the slow job DONE on screen",
                 lambda: driver.find_element(By.CSS_SELECTOR, f"#job-{slow} td.phase").text == "DONE", 120, 0.25)
        assert driver.find_element(By.CSS_SELECTOR, f"#job-{slow} td.eta").text == "0s"

        # The relight view: a frame, then the slider turns the environment.
        driver.get(f"{base}/jobs/{slow}")
        wait_for("a relit frame", lambda: driver.execute_script("return window.wavebakeFrames || 0;") >= 1, 30)
        driver.save_screenshot(str(SHOTS / "job.png"))
        driver.execute_script("document.getElementById('relight-section').scrollIntoView();")
        Select(driver.find_element(By.ID, "probe")).select_by_value("grace.hdr")
        wait_for("the grace frame", lambda: "grace.hdr" in (driver.execute_script(
            "return document.getElementById('relight').dataset.query || '';")), 30)
        pixels = "const c = document.getElementById('relight');" \
                 "return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data);"
        before = driver.execute_script(pixels)
        frames = driver.execute_script("return window.wavebakeFrames;")
        slider = driver.find_element(By.ID, "rotate")
        slider.click()  # focus; a click also moves it to where it lands
        for _ in range(45):
            slider.send_keys(Keys.ARROW_RIGHT)
        wanted = driver.find_element(By.ID, "rotate").get_attribute("value")
        def relit():
            return driver.execute_script(
                "const d = document.getElementById('relight').dataset; return [d.query || '', d.compared || '0'];")
        wait_for("the frame of the new rotation, compared with all lights",
                 lambda: f"rotate={wanted}&" in relit()[0] and relit()[1] == "1", 30)
        after = driver.execute_script(pixels)
        moved = driver.execute_script("return window.wavebakeFrames;") - frames
        differing = sum(1 for a, b in zip(before, after) if abs(a - b) > 8)
        assert len(before) == len(after) == 64 * 64 * 4
        assert differing > 400, f"only {differing} channel values changed"
        stats = driver.find_element(By.ID, "relight-stats").text
        assert "error" in stats and "%" in stats, stats
        driver.save_screenshot(str(SHOTS / "relight.png"))
        print(f"slider to {wanted} deg: {moved} frames, {differing} of {len(before)} channel values changed; {stats}")

        # /metrics parses and agrees with `wavebake status`.
        status, text = http(base + "/metrics", TOKEN)
        assert status == 200
        families = {f.name: f for f in text_string_to_metric_families(text)}
        samples = [x for f in families.values() for x in f.samples]
        kind = lambda name: (families.get(name) or families[name.removesuffix("_total")]).type
        for name, want in (("wavebake_tasks_completed_total", "counter"), ("wavebake_lease_latency_seconds", "histogram"),
                           ("wavebake_jobs", "gauge"), ("wavebake_workers_alive", "gauge")):
            assert kind(name) == want, (name, kind(name))

        def value(name, **labels):
            return sum(x.value for x in samples
                       if x.name == name and all(x.labels.get(k) == v for k, v in labels.items()))

        jobs = [json.loads(line) for line in cli("status", "--json", *client).splitlines()]
        assert {j["id"] for j in jobs} == {slow, queued}
        # Both jobs have finished: no per-job series are left for them (bounded
        # series), their phases are counted in wavebake_jobs; no sample carries
        # a label named job or instance (Prometheus' target labels).
        assert all(j["phase"] in ("DONE", "CANCELLED") for j in jobs), jobs
        assert not [x for x in samples if x.name.startswith("wavebake_job_")], "per-job series of finished jobs"
        assert not [x for x in samples if {"job", "instance"} & set(x.labels)]
        assert kind("wavebake_workers_registered_total") == "counter"
        assert value("wavebake_build_info") == 1 and kind("process_cpu_seconds_total") == "counter"
        assert value("process_open_fds") > 0 and value("process_resident_memory_bytes") > 0
        assert abs(value("process_start_time_seconds") - time.time()) < 600
        if shutil.which("promtool"):
            lint = subprocess.run(["promtool", "check", "metrics"], input=text, text=True,
                                  capture_output=True, timeout=30)
            assert lint.returncode == 0 and not lint.stdout + lint.stderr, lint.stdout + lint.stderr
        completed = value("wavebake_tasks_completed_total")
        assert completed == sum(j["tasks_done"] for j in jobs), completed
        assert value("wavebake_tasks_leased_total") >= completed
        assert value("wavebake_jobs", phase="done") == 1 and value("wavebake_jobs", phase="cancelled") == 1
        assert value("wavebake_workers_alive") == 1
        assert value("wavebake_lease_latency_seconds_count") >= value("wavebake_tasks_leased_total")
        print(f"/metrics: {len(families)} families; completed {completed:.0f} tasks "
              f"= status; screenshots in {SHOTS}")
    finally:
        stop(driver, procs)
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
