#!/usr/bin/env bash
# End-to-end scaling of the service (issue "Service", benchmark 2): the same
# job on a coordinator with 1 worker process, then with 2 worker processes,
# each worker single-threaded (--threads 1), in the same run. Reports the
# job's wall time (first lease to DONE, the coordinator's clock), the workers'
# CPU time, and the speed-up t(1 worker) / t(2 workers). Loopback only. The
# coordinator answers idle workers "ask again in 20 ms" (--lease-wait-ms), so
# the waits at the phase boundaries (the last tile, the last group) stay small.
#
#   bash bench/e2e_workers.sh [build/wavebake] [repeats]
set -euo pipefail
WB=$(realpath "${1:-build/wavebake}")
REPEATS=${2:-2}
BAKE=(builtin:cubes-wall --light-res 32 --supersample 16 --layout camera:64x64 --tile-size 16
      --column-group 1024)
TMP=$(mktemp -d "${TMPDIR:-/tmp}/wb_e2e.XXXXXX")
PIDS=()
cleanup() {
  for pid in "${PIDS[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
  rm -rf "$TMP"
}
trap cleanup EXIT

port() { /usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
field() { /usr/bin/python3 -c "import json,sys; print(json.load(sys.stdin)['$1'])"; }
calc() { /usr/bin/python3 -c "print($1)"; }
cpu_seconds() {  # utime + stime of a live process
  awk -v hz="$(getconf CLK_TCK)" '{print ($14 + $15) / hz}' "/proc/$1/stat"
}

# run WORKERS: prints "wall_s cpu_s" of one job.
run() {
  local workers=$1 dir addr job pids=() cpu=0
  dir=$(mktemp -d "$TMP/run.XXXXXX")
  addr=127.0.0.1:$(port)
  "$WB" coordinator --listen "$addr" --data "$dir" --address-file "$dir/addr" --lease-wait-ms 20 \
    2>"$dir/coord.log" &
  PIDS+=($!)
  local coord=$!
  for _ in $(seq 100); do [[ -s $dir/addr ]] && break; sleep 0.1; done
  for i in $(seq "$workers"); do
    "$WB" worker --coordinator "$addr" --store-root "$dir/store" --threads 1 2>"$dir/w$i.log" &
    pids+=($!)
    PIDS+=($!)
  done
  job=$("$WB" submit "${BAKE[@]}" --coordinator "$addr" --wait 2>/dev/null)
  for pid in "${pids[@]}"; do cpu=$(calc "$cpu + $(cpu_seconds "$pid")"); done
  local json
  json=$("$WB" status "$job" --json --coordinator "$addr")
  local started finished
  started=$(field started_ms <<<"$json")
  finished=$(field finished_ms <<<"$json")
  kill "${pids[@]}" "$coord" 2>/dev/null || true
  wait "${pids[@]}" "$coord" 2>/dev/null || true
  printf "%.3f %.2f\n" "$(calc "($finished - $started) / 1000")" "$cpu"
}

echo "job: ${BAKE[*]}"
echo "workers  wall_s  worker_cpu_s"
best1=1e9 best2=1e9
for r in $(seq "$REPEATS"); do
  read -r w1 c1 < <(run 1)
  echo "1        $w1  $c1"
  read -r w2 c2 < <(run 2)
  echo "2        $w2  $c2"
  best1=$(calc "min($w1, $best1)")
  best2=$(calc "min($w2, $best2)")
done
printf "speed-up (best of %d): %.2f   (1 worker %.2f s, 2 workers %.2f s)\n" "$REPEATS" \
  "$(calc "$best1 / $best2")" "$best1" "$best2"
