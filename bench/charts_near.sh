#!/bin/bash
# The near-field charts of docs/RESULTS.md (9, 10 and the grazing loss):
# builds bench_charts_near, runs it into docs/charts/near_*.csv, plots
# docs/charts/near_*.png with /usr/bin/python3 + matplotlib.
#
#   bash bench/charts_near.sh [BUILD_DIR] [--quick]
#
# Full run: about a minute on two cores (it bakes cubes-wall plane:4 once
# into docs/charts/work, which is not committed); --quick writes to
# BUILD_DIR/charts-near-quick.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="build"
quick=""
for arg in "$@"; do
  case "$arg" in
    --quick) quick="--quick" ;;
    *) build="$arg" ;;
  esac
done
out="$here/docs/charts"
[[ -n "$quick" ]] && out="$build/charts-near-quick"
cmake --build "$build" -j2 --target bench_charts_near
start=$(date +%s)
"$build/bench_charts_near" "$out" $quick --threads "${WB_CHART_THREADS:-2}"
/usr/bin/python3 "$here/bench/charts_near.py" "$out" "$out"
rm -rf "$out/work"
echo "charts: $out ($(( $(date +%s) - start )) s)"
