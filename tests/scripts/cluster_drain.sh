#!/usr/bin/env bash
# `wavebake worker` on SIGTERM (DESIGN.md §4): it drains — leases nothing
# more, finishes and reports the task it is running, and exits 0; the job
# goes on with the next worker.
source "$(dirname "$0")/cluster_lib.bash" "$1"

start_coordinator "$TMP/data" "$(free_port)" --lease-seconds 5
start_worker w1 "$TMP/data/store" --threads 1
w1=$WORKER_PID

# 4 tiles of 16×16 cells at N = 64, K = 256, ~500 Mrays each (13.8 s for
# all four in an embedded bake with one worker): the signal lands inside
# one, with tiles left to lease.
job=$("$WB" submit builtin:disk-over-plane --light-res 64 --supersample 256 --refine off --layout camera:32x32 \
  --tile-size 16 --output-name disk.wbk --coordinator "$ADDR")
wait_until 30 "a tile leased" job_at_least "$job" leased_tasks 1
kill -TERM "$w1"
deadline=$((SECONDS + 30))
while kill -0 "$w1" 2>/dev/null; do
  ((SECONDS < deadline)) || fail "the worker did not exit within 30 s of SIGTERM"
  sleep 0.1
done
wait "$w1" || fail "the drained worker exited with status $?"
# Tiles can finish between the lease and the signal, so the worker may have
# completed more than one; what drain promises is that the task running at
# the signal is finished and reported, nothing is failed or cancelled, and
# nothing more is leased (the job is still unfinished for the next worker).
stopped=$(grep -o "stopped ([0-9]* tasks completed, 0 failed, 0 cancelled)" "$TMP/w1.log") ||
  fail "the drained worker did not stop cleanly: $(tail -n 1 "$TMP/w1.log")"
completed=$(grep -o "[0-9]* tasks completed" <<<"$stopped" | cut -d' ' -f1)
done_lines=$(grep -c "BAKE_TILE [0-9]*: done" "$TMP/w1.log")
((completed >= 1)) || fail "the running tile was not finished"
((completed == done_lines)) || fail "worker reported $completed tasks, logged $done_lines"
((completed < 4)) || fail "the worker kept leasing after SIGTERM (all $completed tiles done)"
job_is "$job" tasks_done "$completed" ||
  fail "tasks_done is $(job_field "$job" tasks_done), expected $completed"
job_is "$job" leased_tasks 0 || fail "the drained worker still holds a lease"

start_worker w2 "$TMP/data/store" --threads 2
timeout 120 "$WB" watch "$job" --coordinator "$ADDR" >/dev/null 2>&1 || fail "the job did not complete"
echo "PASS: SIGTERM drained the worker (its tile finished and reported, exit 0); job $job completed"
