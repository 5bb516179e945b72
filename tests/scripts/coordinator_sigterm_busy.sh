#!/usr/bin/env bash
# Every wait has a bound: SIGTERM to a coordinator whose submit is still busy
# planning (a slow plan, held 10 minutes by the test hook --test-plan-delay-ms,
# as a huge uploaded scene would) ends the process within a few seconds, and
# the data directory is usable by the next coordinator.
source "$(dirname "$0")/cluster_lib.bash" "$1"

start_coordinator "$TMP/data" "$(free_port)" --test-plan-delay-ms 600000
"$WB" submit builtin:furnace --light-res 8 --layout camera:16x16 --coordinator "$ADDR" \
  >"$TMP/submit.log" 2>&1 &
submit=$!
PIDS+=("$submit")
sleep 2  # the submit is inside its plan now
kill -0 "$submit" 2>/dev/null || fail "the submit ended before SIGTERM: $(cat "$TMP/submit.log")"

kill -TERM "$COORD_PID"
start=$SECONDS
# Alive and not a zombie (this shell has not reaped it yet).
alive() { local st; st=$(ps -o stat= -p "$1" 2>/dev/null) && [[ $st != Z* ]]; }
while alive "$COORD_PID"; do
  ((SECONDS - start < 10)) || fail "the coordinator is still alive 10 s after SIGTERM"
  sleep 0.1
done
took=$((SECONDS - start))
wait "$COORD_PID" 2>/dev/null || true
grep -q "shutting down" "$TMP/coordinator.log" || fail "no shutdown in the log"
start_coordinator "$TMP/data" "$(free_port)"  # the lock went with the process
echo "PASS: a coordinator busy planning exited ${took} s after SIGTERM"
