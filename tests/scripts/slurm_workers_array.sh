#!/usr/bin/env bash
# deploy/slurm/workers.sbatch on a real single-node Slurm (started here):
# workers as a two-task job array against a standing coordinator (started
# outside Slurm). The bake ends byte-identical to an embedded one; scancel of
# the array drains both workers (they exit through their SIGTERM drain, not
# a kill).
source "$(dirname "$0")/cluster_lib.bash" "$1"
source "$(dirname "$0")/slurm_lib.bash"
SRC=${WB_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
BAKE=(builtin:cubes-wall --layout camera:32x32 --light-res 16 --supersample 16 --tile-size 8)

"$WB" bake "${BAKE[@]}" --out "$TMP/ref.wbk" >"$TMP/ref.log" 2>&1 || fail "embedded bake failed"
start_slurm
(umask 077 && head -c 32 /dev/urandom | base64 >"$TMP/token")
start_coordinator "$TMP/data" "$(free_port)" --token-file "$TMP/token" --lease-seconds 5
AUTH=(--coordinator "$ADDR" --token-file "$TMP/token")
job=$("$WB" submit "${BAKE[@]}" --output-name array.wbk "${AUTH[@]}")
arr=$(sbatch --parsable --array=0-1 -c2 --output="$TMP/array-%A_%a.log" \
  --export="ALL,WB_BIN=$WB,WB_COORDINATOR=$ADDR,WB_STORE_ROOT=$TMP/data/store,WB_TOKEN_FILE=$TMP/token" \
  "$SRC/deploy/slurm/workers.sbatch") || fail "sbatch refused the array"
timeout 120 "$WB" watch "$job" "${AUTH[@]}" >"$TMP/watch.log" 2>&1 ||
  fail "the bake did not finish: $(tail -n 3 "$TMP/watch.log")"
same_store "$TMP/ref.wbk" "$TMP/data/store/array.wbk"
# A fast bake can end before Slurm starts the second task: wait for it.
for t in 0 1; do
  wait_until 30 "array task $t registered" \
    log_has "$TMP/array-${arr}_$t.log" "registered as \"slurm-${arr}_$t@" 1
done
scancel "$arr" || fail "scancel $arr"
for t in 0 1; do
  wait_slurm_job_end 30 "${arr}_$t"
  log_has "$TMP/array-${arr}_$t.log" "stopped (" 1 ||
    fail "array task $t did not drain: $(tail -n 3 "$TMP/array-${arr}_$t.log")"
done
echo "PASS: job array $arr of 2 workers baked job $job byte-identical; both drained at scancel"
