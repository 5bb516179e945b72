#!/usr/bin/env bash
# A worker whose coordinator forgot it (a new coordinator on a fresh data
# directory at the same address) is told NOT_FOUND and registers again
# (DESIGN.md §4 WorkerService: "an unknown worker_id is NOT_FOUND (register
# again)"), then works for the new coordinator.
source "$(dirname "$0")/cluster_lib.bash" "$1"

port=$(free_port)
TINY=(builtin:furnace --light-res 8 --layout camera:16x16)
start_coordinator "$TMP/data1" "$port" --store-root "$TMP/store"
start_worker w1 "$TMP/store" --threads 1
job=$("$WB" submit "${TINY[@]}" --coordinator "$ADDR" --wait 2>/dev/null) || fail "first job"

kill_now "$COORD_PID"
start_coordinator "$TMP/data2" "$port" --store-root "$TMP/store"
job=$("$WB" submit "${TINY[@]}" --output-name again.wbk --coordinator "$ADDR")
timeout 60 "$WB" watch "$job" --coordinator "$ADDR" >/dev/null 2>&1 ||
  fail "the worker did not come back for the new coordinator"
grep -q "does not know this worker; registering again" "$TMP/w1.log" || fail "no re-registration"
[[ -f $TMP/store/again.wbk/.zattrs ]] || fail "no store from the new coordinator"
echo "PASS: the forgotten worker registered again and baked job $job for the new coordinator"
