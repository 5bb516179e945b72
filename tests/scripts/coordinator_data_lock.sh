#!/usr/bin/env bash
# One coordinator per --data: a second process on the same data directory
# refuses to start and names the pid of the one that holds it; once that one
# has exited (even by SIGKILL) the directory is free again.
source "$(dirname "$0")/cluster_lib.bash" "$1"

start_coordinator "$TMP/data" "$(free_port)"
first=$COORD_PID

second_port=$(free_port)
set +e
timeout 20 "$WB" coordinator --listen "127.0.0.1:$second_port" --data "$TMP/data" \
  >"$TMP/second.log" 2>&1
rc=$?
set -e
((rc != 0 && rc != 124)) || fail "a second coordinator on the same --data ran (rc $rc)"
grep -q "in use by another coordinator (pid $first" "$TMP/second.log" ||
  fail "the refusal does not name pid $first: $(cat "$TMP/second.log")"

kill_now "$first"
start_coordinator "$TMP/data" "$(free_port)"
echo "PASS: a second coordinator on one --data is refused naming pid $first; free again after it exits"
