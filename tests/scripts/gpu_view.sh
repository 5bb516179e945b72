#!/usr/bin/env bash
# Relighting on the browser's GPU (web/views/gpu_view.h, tests/scripts/gpu_view.py):
# `wavebake export --format wavelet-tree` writes what its header documents,
# refuses a visibility store by name, and `wavebake view` serves a page whose
# WebGL2 frame (headless chromium, SwiftShader) equals the C++ decoder's frame
# of the same trees within the float bound, for a camera, a uv and a hilbert
# store at N = 8 and a camera store at N = 16 (whose trees carry jumps).
set -euo pipefail
WB=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
exec /usr/bin/python3 "$(dirname "$0")/gpu_view.py" "$WB"
