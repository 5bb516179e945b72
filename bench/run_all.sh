#!/bin/bash
# `make bench`: every Google Benchmark binary of bench/*.cc in BUILD_DIR, one
# after another, each printing its ratio against the baseline it measures in
# the same run. The chart generators (bench_charts_*) are not benchmarks:
# bench/charts.sh runs them. Exits non-zero if any benchmark fails.
#
#   bash bench/run_all.sh [BUILD_DIR] [extra Google Benchmark flags...]
set -uo pipefail
build="${1:-build}"
shift || true
failed=()
for bin in "$build"/bench_*; do
  name=$(basename "$bin")
  case "$name" in bench_charts_*) continue ;; esac
  [ -x "$bin" ] || continue
  echo "=== $name"
  "$bin" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true "$@" || failed+=("$name")
done
if ((${#failed[@]})); then
  echo "bench: failed: ${failed[*]}" >&2
  exit 1
fi
