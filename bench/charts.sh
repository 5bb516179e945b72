#!/bin/bash
# The charts of docs/RESULTS.md in one command: builds
# bench_charts_data, bench_charts_runtime, bench_charts_uv, bench_charts_glossy,
# bench_charts_near (the near-field charts, bench/charts_near.py) and
# bench_charts_bounces (chart 12, bench/charts_bounces.py), runs the sweeps into
# docs/charts/*.csv, then plots
# docs/charts/*.png with /usr/bin/python3 + matplotlib (Agg).
#
#   bash bench/charts.sh [BUILD_DIR] [--quick]
#
# BUILD_DIR defaults to build. Full run ≈ see docs/RESULTS.md; --quick is a
# few seconds (N = 8, two targets) and writes to BUILD_DIR/charts-quick
# instead, so the committed charts are only ever the full ones.
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
[[ -n "$quick" ]] && out="$build/charts-quick"
cmake --build "$build" -j2 --target bench_charts_data bench_charts_runtime bench_charts_uv \
  bench_charts_glossy bench_charts_near bench_charts_bounces
start=$(date +%s)
"$build/bench_charts_data" "$out" $quick --threads "${WB_CHART_THREADS:-2}"
"$build/bench_charts_runtime" "$out" $quick --threads "${WB_CHART_THREADS:-2}"
# Chart 7 (the lightmap layout; its 512² column stages take most of the time).
"$build/bench_charts_uv" "$out" $quick --threads "${WB_CHART_THREADS:-2}"
# Chart 8 (glossy relighting; six glossy references take most of its time).
"$build/bench_charts_glossy" "$out" $quick --threads "${WB_CHART_THREADS:-2}"
# Charts 9, 10 and the grazing loss (near-field area lights).
"$build/bench_charts_near" "$out" $quick --threads "${WB_CHART_THREADS:-2}"
# Chart 12 (diffuse bounces; its path-traced references take most of the time).
"$build/bench_charts_bounces" "$out" $quick --threads "${WB_CHART_THREADS:-2}"
rm -rf "$out/work"  # the near-field charts' store
/usr/bin/python3 "$here/bench/charts.py" "$out" "$out"
/usr/bin/python3 "$here/bench/charts_near.py" "$out" "$out"
/usr/bin/python3 "$here/bench/charts_bounces.py" "$out" "$out"
echo "charts: $out ($(( $(date +%s) - start )) s)"
