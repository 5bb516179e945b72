"""What the browser tests (gpu_view.py, job_gpu.py, web_monitor.py) share:
a bounded poll and Debian's headless chromium driven through chromedriver."""
import subprocess
import time

from selenium import webdriver
from selenium.webdriver.chrome.service import Service

# Every browser test: no network of chromium's own, a throwaway profile.
COMMON_FLAGS = ("--headless", "--no-sandbox", "--no-first-run", "--disable-background-networking",
                "--disable-component-update", "--disable-sync", "--disable-dev-shm-usage")
# WebGL2 on the CPU (no GPU on the test machines).
SWIFTSHADER_FLAGS = ("--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--disable-gpu-sandbox")


def wait_for(what, predicate, timeout=60, period=0.05):
    """predicate's first true value, polled every `period` s; AssertionError after `timeout` s."""
    deadline = time.time() + timeout
    while True:
        value = predicate()
        if value:
            return value
        if time.time() > deadline:
            raise AssertionError(f"timed out after {timeout}s waiting for {what}")
        time.sleep(period)


def chromium(profile, flags, page_load_timeout=30):
    """Headless chromium with COMMON_FLAGS, `flags` and the profile directory `profile`."""
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for flag in (*COMMON_FLAGS, *flags, f"--user-data-dir={profile}"):
        options.add_argument(flag)
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    driver.set_page_load_timeout(page_load_timeout)
    return driver


def stop(driver, procs):
    """Quits the browser (if started), then ends `procs` newest first: SIGTERM, 20 s, SIGKILL."""
    if driver:
        driver.quit()
    for p in reversed(procs):
        p.terminate()
    for p in procs:
        try:
            p.wait(timeout=20)
        except subprocess.TimeoutExpired:
            p.kill()
