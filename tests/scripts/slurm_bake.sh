#!/usr/bin/env bash
# deploy/slurm/bake.sbatch on a real single-node Slurm (started here): the
# coordinator on the batch host, two worker steps, the store fetched to
# WB_OUT. scancel of one worker step mid-bake still ends in a store
# byte-identical to an embedded bake of the same scene (DESIGN.md §1
# determinism; the lease hands the killed step's tasks to the other).
source "$(dirname "$0")/cluster_lib.bash" "$1"
source "$(dirname "$0")/slurm_lib.bash"
SRC=${WB_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BAKE=(builtin:sphere-plane --layout camera:64x32 --light-res 32 --supersample 36 --refine off --tile-size 8
  --column-group 128)

"$WB" bake "${BAKE[@]}" --out "$TMP/ref.wbk" >"$TMP/ref.log" 2>&1 || fail "embedded bake failed"
start_slurm
start=$SECONDS
job=$(sbatch --parsable -N1 -n1 -c4 --output="$TMP/sbatch-%j.log" \
  --export="ALL,WB_BIN=$WB,WB_DATA=$TMP/data,WB_OUT=$TMP/out.wbk,WB_WORKERS_PER_NODE=2,WB_LEASE_SECONDS=3" \
  "$SRC/deploy/slurm/bake.sbatch" "${BAKE[@]}" --output-name slurm.wbk) || fail "sbatch refused the script"
JD=$TMP/data/slurm-$job
wait_until 60 "the coordinator's address" test -s "$JD/coordinator.addr"
ADDR=$(cat "$JD/coordinator.addr")
TOKEN=(--token-file "$JD/token")
worker_steps() { squeue -h -s -j "$job" -o '%i %j' | awk '$2 == "wavebake-worker" {print $1}'; }
two_steps() { (($(worker_steps | wc -l) == 2)); }
wait_until 60 "two worker steps" two_steps
bake_job() { "$WB" status --json --coordinator "$ADDR" "${TOKEN[@]}" | /usr/bin/python3 -c \
  'import json,sys; print(json.loads(sys.stdin.readline())["id"])'; }
wait_until 30 "the bake job" bake_job
bj=$(bake_job)
tiles_done() { local v; v=$(job_field "$bj" tasks_done "${TOKEN[@]}") && ((v >= 1)); }
wait_until 60 "a tile done" tiles_done
victim=$(worker_steps | head -n 1)
scancel "$victim" || fail "scancel $victim"
done_at=$(job_field "$bj" tasks_done "${TOKEN[@]}")
total=$(job_field "$bj" tasks_total "${TOKEN[@]}")
echo "scancel $victim at $done_at of $total tasks" >&2
((done_at * 2 < total)) || fail "the bake was past half ($done_at of $total) at the scancel: too short"
victim_gone() { ! worker_steps | grep -qxF "$victim"; }
wait_until 20 "step $victim to end" victim_gone
# The rest of the bake runs on the other step alone.
[[ $(job_field "$bj" phase "${TOKEN[@]}") != DONE ]] || fail "the bake ended before the step did"
(($(worker_steps | wc -l) == 1)) || fail "expected one worker step left: $(worker_steps)"
wait_slurm_job_end 120 "$job"
log=$TMP/sbatch-$job.log
[[ $(slurm_job_state "$job") == COMPLETED ]] ||
  fail "Slurm job $job is $(slurm_job_state "$job"): $(tail -n 5 "$log")"
grep -q "store fetched to $TMP/out.wbk" "$log" || fail "no fetch in the job log: $(tail -n 5 "$log")"
same_store "$TMP/ref.wbk" "$TMP/out.wbk"
same_store "$TMP/ref.wbk" "$TMP/data/store/slurm.wbk"
echo "PASS: Slurm job $job baked in $((SECONDS - start)) s; step $victim scancelled mid-bake; store byte-identical to the embedded bake"
