#!/usr/bin/env bash
# The coordinator's --data on a 600 KiB tmpfs that fills up, then gets space
# back. A submit on the full disk fails with RESOURCE_EXHAUSTED and leaves
# nothing: no job listed, no partial store, whether it fails writing its
# store's marker or in SQLite's commit; a cancel either succeeds or
# leaves the job as it was. Once space is freed
# the coordinator serves again without a restart: health SERVING, submit and
# cancel work. Needs root (mount): without it the test fails.
source "$(dirname "$0")/cluster_lib.bash" "$1"

mnt=$TMP/data
mkdir -p "$mnt"
mount -t tmpfs -o size=600k tmpfs "$mnt" || fail "cannot mount a tmpfs at $mnt (this test needs root)"
unmount() {
  local pid
  for pid in "${PIDS[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
  for pid in "${PIDS[@]}"; do wait "$pid" 2>/dev/null || true; done
  umount "$mnt" 2>/dev/null || true
  cleanup
}
trap unmount EXIT

TINY=(builtin:furnace --light-res 8 --layout camera:16x16 --tile-size 4)
start_coordinator "$mnt" "$(free_port)" --lease-seconds 3
first=$("$WB" submit "${TINY[@]}" --coordinator "$ADDR") || fail "submit on an empty disk"

dd if=/dev/zero of="$mnt/filler" bs=4k 2>/dev/null || true  # until the disk is full
set +e
for i in 1 2 3; do
  "$WB" submit "${TINY[@]}" --coordinator "$ADDR" >"$TMP/full$i.out" 2>"$TMP/full$i.err"
  rc=$?
  ((rc != 0)) || fail "submit $i on a full disk succeeded: $(cat "$TMP/full$i.out")"
done
set -e
grep -q "RESOURCE_EXHAUSTED" "$TMP/full1.err" || fail "not RESOURCE_EXHAUSTED: $(cat "$TMP/full1.err")"
# Room for the planner's marker file but not for a larger job's rows: the
# submit gets as far as SQLite's commit and fails there (the case that left
# a QUEUED ghost in memory). Its recovery may take that room, so one try.
truncate -s -4096 "$mnt/filler"
BIG=(builtin:furnace --light-res 8 --layout camera:64x64 --tile-size 4)
if "$WB" submit "${BIG[@]}" --coordinator "$ADDR" >"$TMP/full4.out" 2>"$TMP/full4.err"; then
  fail "a larger submit (SQLite's commit) on a full disk succeeded: $(cat "$TMP/full4.out")"
fi
grep -q "RESOURCE_EXHAUSTED: <data dir>/state.sqlite: No space left on device" "$TMP/full4.err" ||
  fail "the larger submit did not fail in SQLite's commit: $(cat "$TMP/full4.err")"
listed=$("$WB" status --json --coordinator "$ADDR" | wc -l)
((listed == 1)) || fail "$listed jobs listed, expected only job $first (a failed submit left a ghost)"
orphans=$(find "$mnt/store" -maxdepth 1 -name '.job-*.partial' ! -name ".job-$first.wbk.partial" | wc -l)
((orphans == 0)) || fail "failed submits left $orphans partial stores: $(ls -a "$mnt/store")"
# A cancel on the full disk removes the job's store to make room for its
# record; whether that is room enough depends on the page sizes. Either it is
# CANCELLED, or it failed and the job is as the database holds it (QUEUED,
# not CANCELLED in memory alone). (Health is NOT_SERVING only until the
# reaper's recovery commits, which the freed store may already allow.)
if "$WB" cancel "$first" --coordinator "$ADDR" >"$TMP/cancel.out" 2>"$TMP/cancel.err"; then
  job_phase_is "$first" CANCELLED || fail "cancel answered OK but job $first is not CANCELLED"
  cancelled_on_full_disk=1
else
  grep -q "RESOURCE_EXHAUSTED" "$TMP/cancel.err" || fail "cancel: $(cat "$TMP/cancel.err")"
  job_phase_is "$first" QUEUED || fail "job $first after a failed cancel: $(job_field "$first" phase)"
  cancelled_on_full_disk=0
fi

rm -f "$mnt/filler"
wait_until 10 "health SERVING again without a restart" "$WB" health --coordinator "$ADDR"
second=$("$WB" submit "${TINY[@]}" --coordinator "$ADDR") ||
  fail "submit after space came back: $(tail -5 "$TMP/coordinator.log")"
if ((cancelled_on_full_disk == 0)); then
  "$WB" cancel "$first" --coordinator "$ADDR" >/dev/null || fail "cancel after space came back"
fi
job_phase_is "$first" CANCELLED || fail "job $first is not CANCELLED"
[[ ! -e $mnt/store/.job-$first.wbk.partial ]] || fail "the cancelled job's partial store is left"
job_phase_is "$second" QUEUED || fail "job $second is not QUEUED"
echo "PASS: full --data refused submits leaving nothing; recovered without a restart (job $second)"
