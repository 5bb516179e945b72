#!/usr/bin/env bash
# deploy/slurm/bake.sbatch as written, `sbatch -N 3`, on three Slurm nodes
# that are separate hosts (tests/scripts/slurm_hosts.bash: own network and
# UTS namespaces, shared filesystem). Mid-bake one worker node is killed
# outright (its slurmd, its step, its worker: everything in its namespace).
# The job survives (--no-kill), Slurm marks the node down, the node's leased
# tasks move to the other workers when their leases expire, and the store is
# byte-identical to an embedded bake of the same scene (DESIGN.md §1).
source "$(dirname "$0")/cluster_lib.bash" "$1"
source "$(dirname "$0")/slurm_hosts.bash"
SRC=${WB_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BAKE=(builtin:sphere-plane --layout camera:64x32 --light-res 32 --supersample 36 --refine off --tile-size 8
  --column-group 128)

"$WB" bake "${BAKE[@]}" --out "$TMP/ref.wbk" >"$TMP/ref.log" 2>&1 || fail "embedded bake failed"
start_slurm_hosts
start=$SECONDS
job=$(on_ctl sbatch --parsable -N 3 --output="$TMP/sbatch-%j.log" \
  --export="ALL,WB_BIN=$WB,WB_DATA=$TMP/data,WB_STATE=$TMP/local,WB_OUT=$TMP/out.wbk,WB_LEASE_SECONDS=3" \
  "$SRC/deploy/slurm/bake.sbatch" "${BAKE[@]}" --output-name nodes.wbk) || fail "sbatch refused the script"
JD=$TMP/data/slurm-$job
wait_until 60 "the coordinator's address" test -s "$JD/coordinator.addr"
ADDR=$(cat "$JD/coordinator.addr")
[[ $ADDR == "$(host_name 1)":* ]] || fail "the coordinator is not on the batch host $(host_name 1): $ADDR"
C=(--coordinator "$ADDR" --token-file "$JD/token")
three_workers() { (($(grep -l "registered as" "$JD"/worker-*.log 2>/dev/null | wc -l) == 3)); }
wait_until 60 "three workers registered" three_workers
bake_job() { on_ctl "$WB" status --json "${C[@]}" | /usr/bin/python3 -c \
  'import json,sys; print(json.loads(sys.stdin.readline())["id"])'; }
wait_until 30 "the bake job" bake_job
bj=$(bake_job)
field() { on_ctl "$WB" status "$bj" --json "${C[@]}" | /usr/bin/python3 -c \
  "import json,sys; print(json.load(sys.stdin)['$1'])"; }
tiles_done() { (($(field tasks_done) >= 2)); }
wait_until 60 "two tasks done" tiles_done
kill_host 3
done_at=$(field tasks_done)
total=$(field tasks_total)
echo "host 3 killed at $done_at of $total tasks" >&2
((done_at * 2 < total)) || fail "the bake was past half ($done_at of $total) when the node died: too short"
# The other workers are held (SIGSTOP) until Slurm has marked host 3 down, so
# the job is still running when it does, however fast this machine bakes: a
# bake that ended first would not tell whether --no-kill kept it alive.
this_jobs_workers() { pgrep -f -- "worker .*--store-root $TMP/data/store" || true; }
mapfile -t held < <(this_jobs_workers)
((${#held[@]} > 0)) || fail "no worker of this job left to hold"
kill -STOP "${held[@]}"
node_down() { on_ctl sinfo -h -N -n "$(host_name 3)" -o %T | grep -Eq 'down|not_responding|idle\*|alloc\*|mix\*|drain'; }
wait_until 40 "Slurm to see host 3 down" node_down
# Without --no-kill Slurm would end the job here (NODE_FAIL); it runs on.
sleep 2  # what Slurm does on a node failure, it does when it marks the node
state=$(slurm_job_state "$job")
kill -CONT "${held[@]}"
[[ $state == RUNNING ]] || fail "the Slurm job did not survive the node: $state"
wait_slurm_job_end 150 "$job"
log=$TMP/sbatch-$job.log
[[ $(slurm_job_state "$job") == COMPLETED ]] ||
  fail "Slurm job $job is $(slurm_job_state "$job"): $(tail -n 5 "$log")"
grep -q "store fetched to $TMP/out.wbk" "$log" || fail "no fetch in the job log: $(tail -n 5 "$log")"
# Host 3's leases expired and went to the others (`wavebake watch` in the log).
grep -q "lease expired" "$log" || fail "no lease of host 3 expired: $(tail -n 8 "$log")"
same_store "$TMP/ref.wbk" "$TMP/out.wbk"
same_store "$TMP/ref.wbk" "$TMP/data/store/nodes.wbk"
echo "PASS: Slurm job $job (-N 3, three hosts) baked in $((SECONDS - start)) s; host 3 killed at $done_at of $total tasks; store byte-identical to the embedded bake"
