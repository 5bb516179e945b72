#!/usr/bin/env bash
# deploy/slurm/bake.sbatch, `sbatch -N 3` on three separate Slurm hosts
# (tests/scripts/slurm_hosts.bash), loses its coordinator mid-bake (killed on
# the batch host, as a failing host would take it) and is requeued: the rerun
# starts a coordinator on the same node-local state (WB_STATE), which resumes
# the bake, and the script watches the job it submitted before instead of
# submitting again. One bake job in all; the store is byte-identical to an
# embedded bake.
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
  "$SRC/deploy/slurm/bake.sbatch" "${BAKE[@]}" --output-name requeue.wbk) || fail "sbatch refused the script"
JD=$TMP/data/slurm-$job
log=$TMP/sbatch-$job.log
wait_until 60 "the coordinator's address" test -s "$JD/coordinator.addr"
C=(--coordinator "$(cat "$JD/coordinator.addr")" --token-file "$JD/token")
wait_until 30 "the bake job" test -s "$JD/bake.job"
bj=$(cat "$JD/bake.job")
field() { on_ctl "$WB" status "$bj" --json "$@" | /usr/bin/python3 -c \
  "import json,sys; print(json.load(sys.stdin)['tasks_done'])"; }
some_done() { (($(field "${C[@]}") >= 2)); }
wait_until 60 "two tasks done" some_done
# The coordinator of the batch host: found among host 1's processes by its
# command line, killed like its host died under it.
coord=
for pid in $(ns_pids "$(host_ns 1)"); do
  if tr '\0' ' ' <"/proc/$pid/cmdline" 2>/dev/null | grep -q " coordinator --listen"; then coord=$pid; fi
done
[[ -n $coord ]] || fail "no coordinator process on host 1"
kill -KILL "$coord"
wait_slurm_job_end 60 "$job"
grep -q "the coordinator exited" "$log" || fail "the script did not notice its coordinator died: $(tail -n 5 "$log")"
on_ctl scontrol requeue "$job" || fail "scontrol requeue $job"
# Slurm holds a requeued job for two minutes (BeginTime); the test does not
# wait that long, but a node refuses a launch credential made in the second
# it revoked the job's credentials (when the job ended there: "Job
# credential revoked"), so the nodes are idle and a second has passed first.
wait_until 30 "three idle Slurm nodes after the job ended" slurm_hosts_idle
sleep 1.1
on_ctl scontrol update "JobId=$job" StartTime=now || fail "scontrol update $job StartTime=now"
restarted() { (($(grep -c "coordinator at" "$log") >= 2)); }
wait_until 90 "the requeued job's coordinator" restarted
wait_slurm_job_end 120 "$job"
[[ $(slurm_job_state "$job") == COMPLETED ]] ||
  fail "Slurm job $job is $(slurm_job_state "$job") after the requeue: $(tail -n 8 "$log")"
(($(grep -c "bake job .* submitted" "$log") == 1)) || fail "the bake was submitted more than once: $(grep "bake job" "$log")"
grep -q "bake job $bj resumed" "$log" || fail "the rerun did not resume bake job $bj: $(grep "bake job" "$log")"
same_store "$TMP/ref.wbk" "$TMP/out.wbk"
[[ ! -e "$TMP/local/wavebake-$job-$(host_name 1)" ]] || fail "the node-local state was left after DONE"
echo "PASS: Slurm job $job lost its coordinator, was requeued and resumed bake job $bj without a second submit in $((SECONDS - start)) s; store byte-identical to the embedded bake"
