#!/usr/bin/env bash
# The embedded bake under faults: a full disk (a small tmpfs: SQLite, staging
# and the store each run out) ends it at once with an error naming the path
# and "No space left on device", its temporary directory removed and an older
# store at --out untouched; SIGINT and SIGTERM end it within 5 s in every
# phase, leaving nothing but the older store. It used to log "database or disk
# is full" every second forever and ignore both signals.
# Needs root (mount -t tmpfs); the runs have time limits, so a hang fails.
set -euo pipefail
WB=$1
TMP=$(mktemp -d)
DISK=$TMP/disk
mkdir "$DISK"
cleanup() {
  [[ -n ${BAKE_PID:-} ]] && kill -9 "$BAKE_PID" 2>/dev/null
  mountpoint -q "$DISK" && umount "$DISK"
  rm -rf "$TMP"
}
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
BAKE=(builtin:cubes-wall --layout camera:32x32 --light-res 16 --quiet)

# Sizes where SQLite (16k, 128k), staging (400k), the group results (1m) and
# FINALIZE's store (1500k) run out first with --keep-staging, which writes
# staging and group results. The default bake holds both in memory: it runs
# out in SQLite up to 400k and fits from 1m.
for keep in "" --keep-staging; do
  for size in 16k 128k 400k 1m 1500k; do
    mount -t tmpfs -o "size=$size" tmpfs "$DISK" || fail "cannot mount a tmpfs (run as root)"
    start=$SECONDS rc=0
    timeout 30 "$WB" bake "${BAKE[@]}" $keep --out "$DISK/x.wbk" >"$TMP/out.txt" 2>&1 || rc=$?
    ((rc != 124)) || fail "$size$keep: the bake hung on a full disk"
    ((rc != 0)) || { umount "$DISK"; continue; }  # it fit after all: nothing to check
    ((SECONDS - start <= 10)) || fail "$size$keep: took $((SECONDS - start)) s to give up"
    grep -q "No space left on device" "$TMP/out.txt" || fail "$size$keep: $(tail -2 "$TMP/out.txt")"
    grep -qF "$DISK/" "$TMP/out.txt" ||
      fail "$size$keep: the error names no path: $(tail -1 "$TMP/out.txt")"
    (($(grep -c . "$TMP/out.txt") <= 10)) ||
      fail "$size$keep: $(wc -l <"$TMP/out.txt") lines of errors"
    [[ -z $(ls -A "$DISK") ]] || fail "$size$keep: left $(ls -A "$DISK")"
    umount "$DISK"
  done
done

# An older store at --out survives a bake that runs out of space.
mount -t tmpfs -o size=1200k tmpfs "$DISK"
"$WB" bake builtin:cubes-wall --layout camera:16x16 --light-res 8 --quiet --out "$DISK/x.wbk" \
  >/dev/null || fail "the small bake does not fit 1200k"
before=$(cd "$DISK/x.wbk" && find . -type f -exec md5sum {} + | sort)
rc=0
timeout 30 "$WB" bake "${BAKE[@]}" --keep-staging --out "$DISK/x.wbk" >"$TMP/out.txt" 2>&1 || rc=$?
((rc != 0 && rc != 124)) || fail "the second bake: rc $rc"
grep -q "No space left on device" "$TMP/out.txt" || fail "second bake: $(tail -2 "$TMP/out.txt")"
[[ $before == $(cd "$DISK/x.wbk" && find . -type f -exec md5sum {} + | sort) ]] ||
  fail "the older store at --out changed"
[[ $(ls -A "$DISK") == x.wbk ]] || fail "left $(ls -A "$DISK")"
umount "$DISK"

# SIGINT / SIGTERM once the bake is in PHASE (read off its progress on
# stderr; "" = at once, while it plans): gone within 5 s, rc 130, nothing left
# but the older store.
"$WB" bake builtin:cubes-wall --layout camera:16x16 --light-res 8 --quiet --out "$TMP/old.wbk" \
  >/dev/null
before=$(cd "$TMP/old.wbk" && find . -type f -exec md5sum {} + | sort)
interrupt() {
  local signal=$1 phase=$2
  : >"$TMP/err.txt"
  "$WB" bake builtin:cubes-wall --layout camera:64x64 --light-res 32 --supersample 16 --refine off \
    --workers 2 --out "$TMP/old.wbk" 2>"$TMP/err.txt" >/dev/null &
  BAKE_PID=$!
  local deadline=$((SECONDS + 60))
  if [[ -n $phase ]]; then
    until tr '\r' '\n' <"$TMP/err.txt" | grep -q "^$phase"; do
      ((SECONDS < deadline)) || fail "$signal: the bake never reached '$phase'"
      kill -0 "$BAKE_PID" 2>/dev/null || fail "$signal: the bake ended before '$phase'"
      sleep 0.05
    done
  else
    sleep 0.2
  fi
  kill -"$signal" "$BAKE_PID"
  local sent=$SECONDS rc=0
  for _ in $(seq 50); do kill -0 "$BAKE_PID" 2>/dev/null || break; sleep 0.1; done
  kill -0 "$BAKE_PID" 2>/dev/null && fail "SIG$signal in '$phase': still running after 5 s"
  wait "$BAKE_PID" || rc=$?
  BAKE_PID=
  ((rc == 130)) || fail "SIG$signal in '$phase': rc $rc: $(tail -c 300 "$TMP/err.txt")"
  [[ $(ls -A "$TMP" | grep -v -e '^old.wbk$' -e '^err.txt$' -e '^disk$' -e '^out.txt$') == "" ]] ||
    fail "SIG$signal in '$phase' left $(ls -A "$TMP")"
  [[ $before == $(cd "$TMP/old.wbk" && find . -type f -exec md5sum {} + | sort) ]] ||
    fail "SIG$signal in '$phase' changed the older store"
  echo "SIG$signal in '${phase:-planning}': ended in <= $((SECONDS - sent + 1)) s"
}
interrupt INT ""
interrupt INT "bake tiles"
interrupt TERM "transform columns"
interrupt INT "finalize"
echo "PASS: a full disk ends the bake at once, naming the path; signals end it within 5 s"
