#!/usr/bin/env bash
# The bake-speed goals, each printed as a ratio against a baseline measured in
# the same run (medians of 3 where a benchmark repeats):
#   * row loop: the fastest raw Embree kernel's CPU time over TransportRow's
#     on the same rays, measured row by row in one benchmark
#     (bench_transport BM_TransportRowPaired, target >= 0.85);
#   * column stage: its CPU time over the brute-force trace's of the same job
#     (bench_column_stage BM_ColumnStage, x_trace_cpu; target <= 0.25) on the
#     bunny (hilbert 64x64, N=32) and cubes-wall (camera 256x256, N=64);
#   * refinement against brute force, whole bakes (bench_refine_bake: rays,
#     wall and CPU time, eval --reference error under grace and pisa).
#
#   bench/speed_goals.sh BUILD_DIR WORK_DIR [--quick]
#
# --quick: column stage on the bunny only, bench_refine_bake --quick. The
# machine's load inflates wall times; the CPU ratios are the steadier ones.
set -euo pipefail
build=${1:?usage: speed_goals.sh BUILD_DIR WORK_DIR [--quick]}
work=${2:?usage: speed_goals.sh BUILD_DIR WORK_DIR [--quick]}
quick=${3:-}
mkdir -p "$work"
py=/usr/bin/python3
reps=(--benchmark_repetitions=3 --benchmark_report_aggregates_only=true --benchmark_format=json)

# median COUNTER of benchmark NAME_PREFIX in a Google Benchmark JSON file
median() {
  "$py" - "$1" "$2" "$3" <<'PY'
import json, sys
path, name, counter = sys.argv[1:]
for b in json.load(open(path))["benchmarks"]:
    if b.get("aggregate_name") == "median" and b["run_name"] == name:
        print(f'{b[counter]:.3f}')
        break
else:
    sys.exit(f"{name} {counter}: not in {path}")
PY
}
mark() { "$py" -c "import sys; print('ok' if $1 else 'MISSED')"; }

echo "== row loop (bench_transport)" >&2
"$build/bench_transport" --benchmark_filter=BM_TransportRowPaired "${reps[@]}" \
  > "$work/transport.json"
row=$(median "$work/transport.json" BM_TransportRowPaired x_fastest_kernel_paired)

cases=(bunny cubes-wall)
[[ $quick == --quick ]] && cases=(bunny)
declare -A col col_wall
for c in "${cases[@]}"; do
  echo "== column stage, $c (bench_column_stage)" >&2
  "$build/bench_column_stage" --case="$c" --benchmark_filter='BM_ColumnStage' "${reps[@]}" \
    > "$work/column-$c.json"
  col[$c]=$(median "$work/column-$c.json" BM_ColumnStage/threads:2/real_time x_trace_cpu)
  col_wall[$c]=$(median "$work/column-$c.json" BM_ColumnStage/threads:2/real_time x_trace)
done

echo "== refinement against brute force (bench_refine_bake)" >&2
"$build/bench_refine_bake" "$work/bakes" ${quick:+--quick} | tee "$work/refine_bake.txt" | head -n -1

echo
echo "row loop: TransportRow / fastest raw kernel = $row x (target >= 0.85: $(mark "$row >= 0.85"))"
for c in "${cases[@]}"; do
  echo "column stage / brute-force trace, $c: CPU ${col[$c]} x, wall ${col_wall[$c]} x" \
    "(target <= 0.25: $(mark "${col[$c]} <= 0.25"))"
done
