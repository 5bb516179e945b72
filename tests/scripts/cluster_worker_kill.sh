#!/usr/bin/env bash
# DESIGN.md §4 "a lease that is not renewed in time returns its task to the
# queue": a coordinator and two worker processes on loopback; one worker is
# SIGKILLed while tiles are baking. The job still completes, the killed
# worker's lease expired (its task was requeued), and the store is
# bit-identical (every file's bytes) to an embedded `wavebake bake` of the same
# scene and parameters, whichever worker ran which task (DESIGN.md §1
# "Determinism").
source "$(dirname "$0")/cluster_lib.bash" "$1"

# 16 tiles of 8×8 cells, each long enough (N = 32, K = 256: ~40 Mrays, 7.0 s
# for all sixteen and the column stage in an embedded bake with one worker)
# that neither the gap between two tasks nor a status poll on a loaded
# machine is likely to span the kill: the victim must hold a lease when it
# dies, and the job must still be baking.
BAKE=(builtin:cubes-wall --light-res 32 --supersample 256 --refine off --layout camera:32x32
      --tile-size 8 --column-group 512)

start_coordinator "$TMP/data" "$(free_port)" --lease-seconds 2
start_worker w1 "$TMP/data/store" --threads 1
victim=$WORKER_PID
start_worker w2 "$TMP/data/store" --threads 1

job=$("$WB" submit "${BAKE[@]}" --output-name cubes.wbk --coordinator "$ADDR")
wait_until 60 "two tiles done" job_at_least "$job" tasks_done 2
job_phase_is "$job" BAKING || fail "the job left BAKING before the kill; make its tiles longer"
grep -q "BAKE_TILE" "$TMP/w1.log" || fail "w1 has run no tile"
kill_now "$victim"

"$WB" watch "$job" --coordinator "$ADDR" >"$TMP/watch.out" 2>"$TMP/watch.err" ||
  fail "watch: job did not complete: $(cat "$TMP/watch.out" "$TMP/watch.err")"
grep -q "lease expired" "$TMP/watch.err" || fail "no lease expired: was w1 killed between tasks?"

# The reference: the embedded default, two in-process workers.
"$WB" bake "${BAKE[@]}" --workers 2 --quiet --out "$TMP/ref.wbk" >/dev/null
same_store "$TMP/ref.wbk" "$TMP/data/store/cubes.wbk"
# And the copy a client fetches over gRPC.
"$WB" fetch "$job" --out "$TMP/fetched.wbk" --coordinator "$ADDR" >/dev/null
same_store "$TMP/ref.wbk" "$TMP/fetched.wbk"
[[ -z $(find "$TMP/data/store" -maxdepth 1 -name '.*partial*') ]] || fail "partial store left behind"
echo "PASS: worker killed mid-bake; job $job completed, store bit-identical to the embedded bake"
