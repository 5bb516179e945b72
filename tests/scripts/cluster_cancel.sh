#!/usr/bin/env bash
# DESIGN.md §4 Cancel: a running job is cancelled; its worker stops the task
# within a few seconds (the heartbeat withdraws the lease, the tile checks its
# cancel flag between rows), no staging or partial store is left, and the
# worker goes on to the next job.
source "$(dirname "$0")/cluster_lib.bash" "$1"

start_coordinator "$TMP/data" "$(free_port)" --lease-seconds 3
start_worker w1 "$TMP/data/store" --threads 2

# Two tiles of 32×32 cells at N = 64, K = 256: neither had finished 8 s into
# an embedded bake on 2 cores, so the cancel surely lands inside them (at
# N = 32, K = 64 the faster row loop finished them in 1.6 s, sometimes
# before the cancel came).
job=$("$WB" submit builtin:sphere-plane --light-res 64 --supersample 256 --refine off --layout camera:64x32 \
  --tile-size 32 --output-name big.wbk --coordinator "$ADDR")
wait_until 30 "both tiles leased" job_at_least "$job" leased_tasks 2
wait_until 30 "the tiles started" test -d "$TMP/data/store/.big.wbk.partial/staging"
sleep 0.5
start=$(date +%s%N)
"$WB" cancel "$job" --coordinator "$ADDR" | grep -q CANCELLED || fail "cancel did not say CANCELLED"
wait_until 5 "the worker stopped both tasks" log_has "$TMP/w1.log" "lease was cancelled" 2
wait_until 10 "the leases dropped" job_is "$job" leased_tasks 0
echo "tasks stopped and leases dropped $((($(date +%s%N) - start) / 1000000)) ms after the cancel" >&2
wait_until 10 "the partial store removed" test ! -e "$TMP/data/store/.big.wbk.partial"
[[ ! -e $TMP/data/store/big.wbk ]] || fail "a store was left at the output path"
job_phase_is "$job" CANCELLED || fail "job is $(job_field "$job" phase)"
"$WB" watch "$job" --coordinator "$ADDR" >/dev/null 2>&1 && fail "watch of a cancelled job exited 0"

# The worker is free again: a small job completes.
next=$("$WB" submit builtin:furnace --light-res 8 --layout camera:16x16 --coordinator "$ADDR")
timeout 60 "$WB" watch "$next" --coordinator "$ADDR" >/dev/null 2>&1 || fail "the next job did not complete"
echo "PASS: job $job cancelled; tasks stopped, nothing left behind; job $next ran after it"
