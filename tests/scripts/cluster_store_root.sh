#!/usr/bin/env bash
# Workers check their configuration at start (storage/store/store_root_marker.h):
# a --store-root that is the coordinator's data dir (not its store/), a
# directory that does not exist (an NFS mount that is missing), another
# coordinator's store root, or a read-only one makes `worker` exit non-zero
# within 5 s with a message naming --store-root and what it expected, before
# it leases anything, so the job that is waiting loses no attempt to it and
# bakes once a correct worker comes.
source "$(dirname "$0")/cluster_lib.bash" "$1"

start_coordinator "$TMP/data" "$(free_port)" --lease-seconds 3
job=$("$WB" submit builtin:furnace --light-res 8 --layout camera:16x16 --max-attempts 1 \
  --coordinator "$ADDR")
"$WB" coordinator --listen 127.0.0.1:0 --data "$TMP/other" --address-file "$TMP/other.addr" \
  >"$TMP/other.log" 2>&1 &
other=$!
PIDS+=("$other")
wait_until 20 "the second coordinator" test -s "$TMP/other.addr"
kill_now "$other"
mkdir -p "$TMP/ro"
cp "$TMP/data/store/.wavebake-store-root" "$TMP/ro/"

# refused NAME PATTERN STORE_ROOT [LAUNCHER...]: `worker` exits non-zero
# within 5 s with a message naming --store-root and matching PATTERN.
refused() {
  local name=$1 pattern=$2 root=$3
  shift 3
  local t0=$SECONDS rc=0
  timeout 10 "$@" "$WB" worker --coordinator "$ADDR" --store-root "$root" --name "$name" \
    --threads 1 >"$TMP/$name.log" 2>&1 || rc=$?
  ((rc != 0 && rc != 124)) || fail "$name: worker exit $rc, expected a refusal"
  ((SECONDS - t0 <= 5)) || fail "$name: refused after $((SECONDS - t0)) s (> 5 s)"
  grep -q -- "--store-root $root" "$TMP/$name.log" || fail "$name: message does not name --store-root"
  grep -q -- "$pattern" "$TMP/$name.log" || fail "$name: no \"$pattern\" in: $(tail -n 2 "$TMP/$name.log")"
}
refused data-dir "did you mean $TMP/data/store" "$TMP/data"
refused missing "no such directory" "$TMP/nfs/store"
refused foreign "another coordinator" "$TMP/other/store"
# Root writes through permission bits: a read-only bind mount, in a mount
# namespace of the worker's own (nothing to unmount afterwards).
refused read-only "not writable" "$TMP/ro" unshare -m sh -c \
  'mount --bind "$0" "$0" && mount -o remount,ro,bind "$0" && exec "$@"' "$TMP/ro"
for name in data-dir missing foreign read-only; do
  grep -q "expected the coordinator's store root" "$TMP/$name.log" ||
    fail "$name: the message does not say what was expected"
done

job_is "$job" tasks_done 0 || fail "a refused worker ran a task"
[[ $(job_field "$job" leased_tasks) == 0 ]] || fail "a refused worker holds a lease"
start_worker good "$TMP/data/store" --threads 1
# With --max-attempts 1 any failed or expired task would have failed the job.
timeout 60 "$WB" watch "$job" --coordinator "$ADDR" >"$TMP/watch.log" 2>&1 ||
  fail "the job did not finish after the refusals: $(tail -n 2 "$TMP/watch.log")"
echo "PASS: 4 wrong store roots refused within 5 s, naming --store-root; job $job baked (max-attempts 1)"
