# Helpers of the multi-process cluster tests (tests/scripts/cluster_*.sh),
# sourced, not run. Loopback only; every wait is bounded; every process
# started here is killed on exit (by its pid, nothing else).
#
#   source cluster_lib.bash "$wavebake_binary"
#   port=$(free_port)
#   start_coordinator DIR PORT [flags...]   # sets COORD_PID; waits until it serves
#   start_worker NAME STORE_ROOT [flags...] # sets WORKER_PID; log in $TMP/NAME.log
#   wait_until TIMEOUT_S DESCRIPTION COMMAND...
set -euo pipefail

WB=${1:?usage: bash $0 path/to/wavebake}
WB=$(cd "$(dirname "$WB")" && pwd)/$(basename "$WB")
TMP=$(mktemp -d "${TMPDIR:-/tmp}/wb_cluster_test.XXXXXX")
PIDS=()

cleanup() {
  local pid
  for pid in "${PIDS[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
  for pid in "${PIDS[@]}"; do wait "$pid" 2>/dev/null || true; done
  if [[ ${KEEP_TMP:-0} == 1 ]]; then echo "kept $TMP" >&2; else rm -rf "$TMP"; fi
}
trap cleanup EXIT

fail() {
  echo "FAIL: $*" >&2
  for log in "$TMP"/*.log; do
    [[ -f $log ]] || continue
    echo "---- $log (tail)" >&2
    tail -n 25 "$log" >&2
  done
  exit 1
}

# A TCP port nobody listens on right now (the kernel's choice).
free_port() {
  /usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

# wait_until TIMEOUT_S DESCRIPTION COMMAND...: polls COMMAND every 0.1 s.
wait_until() {
  local timeout=$1 what=$2
  shift 2
  local deadline=$((SECONDS + timeout))
  until "$@" >/dev/null 2>&1; do
    ((SECONDS < deadline)) || fail "timed out after ${timeout}s waiting for: $what"
    sleep 0.1
  done
}

start_coordinator() {
  local dir=$1 port=$2
  shift 2
  rm -f "$TMP/coordinator.addr"
  "$WB" coordinator --listen "127.0.0.1:$port" --data "$dir" \
    --address-file "$TMP/coordinator.addr" "$@" >>"$TMP/coordinator.log" 2>&1 &
  COORD_PID=$!
  PIDS+=("$COORD_PID")
  wait_until 20 "coordinator on port $port" test -s "$TMP/coordinator.addr"
  ADDR=127.0.0.1:$port
}

start_worker() {
  local name=$1 root=$2
  shift 2
  "$WB" worker --coordinator "$ADDR" --store-root "$root" --name "$name" "$@" \
    >>"$TMP/$name.log" 2>&1 &
  WORKER_PID=$!
  PIDS+=("$WORKER_PID")
}

# job_field JOB FIELD [client flags...]: one field of `status --json`.
job_field() {
  local job=$1 field=$2
  shift 2
  "$WB" status "$job" --json --coordinator "$ADDR" "$@" |
    /usr/bin/python3 -c "import json, sys; print(json.load(sys.stdin)['$field'])"
}

# job_at_least JOB FIELD N: the field (a number) is >= N.
job_at_least() {
  local v
  v=$(job_field "$1" "$2") || return 1
  ((v >= $3))
}

# log_has FILE PATTERN N: at least N lines of FILE match PATTERN.
log_has() {  # a log not written yet has no lines
  local n
  n=$(grep -c -- "$2" "$1" 2>/dev/null) || true
  ((${n:-0} >= $3))
}

# job_is JOB FIELD VALUE
job_is() { [[ $(job_field "$1" "$2") == "$3" ]]; }

# kill_now PID: SIGKILL, reaped quietly (no "Killed" line from the shell).
kill_now() { { kill -9 "$1" && wait "$1"; } 2>/dev/null || true; }

job_phase_is() { [[ $(job_field "$1" phase) == "$2" ]]; }

# Every file of two stores has the same bytes, and they hold the same files.
same_store() {
  diff -r "$1" "$2" >"$TMP/diff.txt" 2>&1 || fail "stores differ: $(head -c 600 "$TMP/diff.txt")"
}
