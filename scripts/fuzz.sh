#!/usr/bin/env bash
# Runs every libFuzzer harness of a -DWB_FUZZ=ON build for a bounded time, a
# few at a time, each from its seed corpus (tests/fuzz/<name>/corpus/, left
# unchanged: new inputs go to a temporary directory). Fails on any finding —
# crash, sanitizer report, leak, timeout (-timeout), memory blow-up — and says
# where its reproducer is. Prints each fuzzer's executions per second.
#
#   bash scripts/fuzz.sh BUILD_DIR [SECONDS_EACH=30] [AT_ONCE=2]
set -euo pipefail
BUILD=${1:?usage: bash scripts/fuzz.sh BUILD_DIR [SECONDS_EACH] [AT_ONCE]}
SECONDS_EACH=${2:-30}
AT_ONCE=${3:-2}
# A fixed seed makes CI's runs repeat the same mutations (a new finding then
# means a change, not luck); FUZZ_SEED=0 lets libFuzzer pick one, to explore.
SEED=${FUZZ_SEED:-1}
SRC=$(cd "$(dirname "$0")/.." && pwd)
OUT=$(mktemp -d "${TMPDIR:-/tmp}/wb_fuzz_run.XXXXXX")
export LSAN_OPTIONS="suppressions=$SRC/tests/lsan.supp"
export ASAN_OPTIONS="${ASAN_OPTIONS:-}${ASAN_OPTIONS:+:}abort_on_error=1"

mapfile -t harnesses < <(find "$BUILD/tests/fuzz" -maxdepth 1 -name 'fuzz_*' -type f -executable | sort)
((${#harnesses[@]})) || { echo "fuzz: no harnesses in $BUILD/tests/fuzz (build with -DWB_FUZZ=ON)" >&2; exit 1; }

run_one() {  # run_one BINARY: its log is $OUT/NAME.log, its verdict $OUT/NAME.rc
  local bin=$1 name=${1##*/fuzz_} rc=0
  mkdir -p "$OUT/$name.corpus"
  "$bin" -seed="$SEED" -max_total_time="$SECONDS_EACH" -timeout=10 -rss_limit_mb=2560 -print_final_stats=1 \
    -artifact_prefix="$OUT/$name-" "$OUT/$name.corpus" "$SRC/tests/fuzz/$name/corpus" \
    >"$OUT/$name.log" 2>&1 || rc=$?
  echo "$rc" >"$OUT/$name.rc"
}

pids=()
for bin in "${harnesses[@]}"; do
  run_one "$bin" &
  pids+=($!)
  if ((${#pids[@]} >= AT_ONCE)); then wait "${pids[0]}"; pids=("${pids[@]:1}"); fi
done
wait

failed=0
for bin in "${harnesses[@]}"; do
  name=${bin##*/fuzz_}
  rc=$(cat "$OUT/$name.rc")
  runs=$(grep -oE 'stat::number_of_executed_units:[[:space:]]+[0-9]+' "$OUT/$name.log" |
    grep -oE '[0-9]+$' || echo 0)
  rate=$(grep -oE 'stat::average_exec_per_sec:[[:space:]]+[0-9]+' "$OUT/$name.log" |
    grep -oE '[0-9]+$' || echo 0)
  printf 'fuzz %-8s %9s runs %7s exec/s  %s\n' "$name" "$runs" "$rate" \
    "$( ((rc == 0)) && echo ok || echo "FINDING (rc $rc)")"
  if ((rc != 0)); then
    failed=1
    grep -E 'ERROR|SUMMARY|invariant violated|runtime error|Test unit written' "$OUT/$name.log" |
      head -8 >&2 || true
  fi
done
if ((failed)); then
  echo "fuzz: findings above; logs and reproducers kept in $OUT" >&2
  exit 1
fi
rm -rf "$OUT"
