#!/usr/bin/env bash
# DESIGN.md §4 Cancel inside the column stage: a TRANSFORM_COLUMNS task of
# one large group stops within a heartbeat of the cancel (the task checks its
# cancel flag between staging chunks and columns), not when the group is done.
# The same group uncancelled, baked first, shows how long it would have run.
source "$(dirname "$0")/cluster_lib.bash" "$1"

start_coordinator "$TMP/data" "$(free_port)" --lease-seconds 3  # heartbeat every ~1 s
start_worker w1 "$TMP/data/store" --threads 1
JOB=(builtin:cubes-wall --layout camera:128x128 --light-res 32 --supersample 1 --column-group 6144 --column-terms 4096)
ref=$("$WB" submit "${JOB[@]}" --output-name whole.wbk --coordinator "$ADDR")
timeout 120 "$WB" watch "$ref" --coordinator "$ADDR" >/dev/null 2>&1 || fail "the reference job failed"
full=$(sed -n 's/.*TRANSFORM_COLUMNS 0: done in \([0-9.]*\) s.*/\1/p' "$TMP/w1.log")
[[ -n $full ]] || fail "no TRANSFORM_COLUMNS timing in the worker log"
awk -v d="$full" 'BEGIN { exit !(d >= 2.5) }' || fail "the group took only $full s: too short to test"

job=$("$WB" submit "${JOB[@]}" --output-name cut.wbk --coordinator "$ADDR")
transforming() { job_phase_is "$job" TRANSFORMING && job_is "$job" leased_tasks 1; }
wait_until 120 "the group leased" transforming
sleep 0.3
"$WB" cancel "$job" --coordinator "$ADDR" | grep -q CANCELLED || fail "cancel did not say CANCELLED"
wait_until 5 "the group task stopped" log_has "$TMP/w1.log" "TRANSFORM_COLUMNS 0 stopped: its lease was cancelled" 1
ran=$(sed -n 's/.*TRANSFORM_COLUMNS 0: CANCELLED.* in \([0-9.]*\) s.*/\1/p' "$TMP/w1.log")
[[ -n $ran ]] || fail "no timing of the stopped task"
awk -v r="$ran" -v d="$full" 'BEGIN { exit !(r < 0.75 * d) }' ||
  fail "the stopped group ran $ran s of its $full s: the cancel was not seen inside it"
wait_until 10 "the partial store removed" test ! -e "$TMP/data/store/.cut.wbk.partial"
echo "PASS: TRANSFORM_COLUMNS stopped after $ran s of $full s, within a heartbeat of the cancel"
