#!/bin/bash
# Chart 11 of docs/RESULTS.md in one command: relighting on the GPU in both
# modes (wavelet trees, the 4D store) beside the CPU relighter, on spot.obj
# uv:128x128, N = 32, under grace.hdr with 256 wavelet lights.
#
#   bash bench/gpu_modes.sh [BUILD_DIR] [--real-gpu] [--quick]
#
# Bakes the store (about 30 s), traces the reference once for the errors of
# every tree setting and of the store (`wavebake eval --tree-cut-off`, about
# 2 min), then bench/gpu_modes.py times both modes in headless chromium
# (SwiftShader unless --real-gpu: then ANGLE uses the machine's GPU) and the
# CPU relighter on the same store and lights, and bench/gpu_modes_chart.py
# plots docs/charts/gpu_modes.png from docs/charts/gpu_modes.csv. --quick:
# a 32x32 camera store, no errors, output under BUILD_DIR/charts-quick.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="build" gpu="" quick=""
for arg in "$@"; do
  case "$arg" in
    --real-gpu) gpu="--real-gpu" ;;
    --quick) quick=1 ;;
    *) build="$arg" ;;
  esac
done
wb="$(cd "$build" && pwd)/wavebake"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
data="$here/../shared/data"
cuts=(default 4e-5 5e-5 6e-5 7e-5 1e-4 2e-4 4e-4)
if [[ -n "$quick" ]]; then
  out="$build/charts-quick"
  mkdir -p "$out"
  "$wb" bake builtin:disk-over-plane --layout camera:32x32 --light-res 8 --quiet --out "$tmp/s.wbk" >/dev/null
  /usr/bin/python3 "$here/bench/gpu_modes.py" "$wb" "$tmp/s.wbk" --frames 5 --cut-off default \
    --cut-off 1e-3 $gpu --csv "$out/gpu_modes.csv"
  exit 0
fi
out="$here/docs/charts"
"$wb" bake "$data/models/spot.obj" --layout uv:128x128 --light-res 32 --quiet --out "$tmp/spot.wbk" >/dev/null
args=()
for c in "${cuts[@]}"; do args+=(--tree-cut-off "$c"); done
(cd "$data/models" && "$wb" eval "$tmp/spot.wbk" --env ../probes/grace.hdr --reference --terms 256 \
  "${args[@]}" --json >"$tmp/eval.json" 2>/dev/null)
args=()
for c in "${cuts[@]}"; do args+=(--cut-off "$c"); done
/usr/bin/python3 "$here/bench/gpu_modes.py" "$wb" "$tmp/spot.wbk" --probes "$data/probes" \
  --probe grace.hdr --terms 256 --frames 20 "${args[@]}" $gpu --eval-json "$tmp/eval.json" \
  --csv "$out/gpu_modes.csv"
/usr/bin/python3 "$here/bench/gpu_modes_chart.py" "$out/gpu_modes.csv" "$out/gpu_modes.png"
