#!/usr/bin/env bash
# The web monitor in a real browser (headless Debian chromium driven by
# python3-selenium): a coordinator with --http and a worker, the pages, live
# progress, cancel, the relight view's slider, 401 without the token, and
# /metrics against `wavebake status` (tests/scripts/web_monitor.py).
set -euo pipefail
WB=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
exec /usr/bin/python3 "$(dirname "$0")/web_monitor.py" "$WB"
