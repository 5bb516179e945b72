#!/usr/bin/env bash
# DESIGN.md §4 "The coordinator keeps jobs and tasks in SQLite (WAL) and
# resumes after a restart": the coordinator is SIGKILLed mid-job and started
# again on the same data directory and port; the workers ride it out, the job
# resumes and completes, bit-identical to an embedded bake.
source "$(dirname "$0")/cluster_lib.bash" "$1"

# 16 tiles of ~0.25 s each (N = 32, K = 128: ~15 Mrays): still BAKING when
# the status poll sees three done, with a second to spare.
BAKE=(builtin:cylinder-bump --light-res 32 --supersample 128 --refine off --layout camera:32x32
      --tile-size 8 --column-group 512)
port=$(free_port)

start_coordinator "$TMP/data" "$port" --lease-seconds 3
start_worker w1 "$TMP/data/store" --threads 1
start_worker w2 "$TMP/data/store" --threads 1

job=$("$WB" submit "${BAKE[@]}" --output-name bump.wbk --coordinator "$ADDR")
wait_until 60 "three tiles done" job_at_least "$job" tasks_done 3
job_phase_is "$job" BAKING || fail "the job left BAKING before the kill; make its tiles longer"
kill_now "$COORD_PID"
sleep 1
start_coordinator "$TMP/data" "$port" --lease-seconds 3

"$WB" watch "$job" --coordinator "$ADDR" >"$TMP/watch.out" 2>"$TMP/watch.err" ||
  fail "watch: job did not complete: $(cat "$TMP/watch.out" "$TMP/watch.err")"
grep -q "coordinator restarted" "$TMP/watch.err" || fail "no RESUMED event in the job's history"

"$WB" bake "${BAKE[@]}" --workers 2 --quiet --out "$TMP/ref.wbk" >/dev/null
same_store "$TMP/ref.wbk" "$TMP/data/store/bump.wbk"
echo "PASS: coordinator killed and restarted; job $job resumed and completed bit-identically"
