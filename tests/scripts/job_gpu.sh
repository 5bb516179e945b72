#!/usr/bin/env bash
# The job page's relight view on the browser's GPU (web/views/job_gpu.h): headless
# chromium with SwiftShader draws a finished job's store from its arrays,
# and turning the rotation slider fetches only the kept lights — no frame
# request (tests/scripts/job_gpu.py counts them).
set -euo pipefail
WB=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
exec /usr/bin/python3 "$(dirname "$0")/job_gpu.py" "$WB"
